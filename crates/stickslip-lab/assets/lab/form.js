// The form of the model's values, built from the server's key table (/api/keys): one field
// per key of `form`, in the table's order, in the fieldset for the systems it is shown for,
// labelled with the key's symbol, titled with its help; a "fit" box on the values a fit of
// a circuit may free (`fit.parameters`), shown for the diode laws whose parameter it is
// (`fit.by_law`), ticked on those a fit of such a law frees by default (`fit.free`, by law).
// The rest of the page asks this module which keys each system has (the query it sends, the
// fields a preset fills), which a fit may free by diode law, and each key's symbol and unit:
// no list of the model's keys is written anywhere else.

import { $, num, siText } from './util.js';

/** The served key table (/api/keys), kept by `buildForm`: the form's fields in the table's
 * order, each key's row by its flag, and what a fit may free. */
const served = { form: [], keys: new Map(), fit: { parameters: [], by_law: {}, free: {} } };

/** The flags of the fields shown for `system` (`pwl`, `shockley`, `mechanics`: the fieldsets'
 * `data-for-system`), in the table's order. */
export const fieldsOf = (system) => served.form.filter((f) => f.fieldset.split(' ').includes(system)).map((f) => f.flag);

/** The flag of the field that chooses the friction law (served `chooses_law`), if any. */
const lawChooser = () => served.form.find((f) => f.chooses_law)?.flag;

/** The friction law chosen now (`coulomb`, `stribeck`, `cubic`: the chooser's value). */
export const chosenLaw = () => {
  const flag = lawChooser();
  return flag ? $(`[name="${CSS.escape(flag)}"]`).value : null;
};

/** Whether a field is sent and shown now: a friction law's parameter (served `law`) only
 * while that law is chosen. */
export const inUse = (flag) => {
  const f = served.form.find((g) => g.flag === flag);
  return !f || !f.law || f.law === chosenLaw();
};

/** The flags of the fields of `system` sent with a query: those of its fieldsets in use
 * (`inUse`), in the table's order. */
export const sentFieldsOf = (system) => fieldsOf(system).filter(inUse);

/** Show the chosen law's parameters and hide the others'. */
export function showLawFields() {
  for (const f of served.form) {
    if (!f.law) continue;
    $(`[name="${CSS.escape(f.flag)}"]`).closest('.field').hidden = f.law !== chosenLaw();
  }
}

/** The flag of the law chooser, for the page's wiring (its change shows other fields). */
export const lawChooserFlag = () => lawChooser();

/** Whether the field is a part of the circuit (L, C, R, U_t, R_D: a preset gives them). */
export const isPart = (flag) => served.form.some((f) => f.flag === flag && f.part);

/** The fit parameters of a diode law (`pwl`, `shockley`) that have a field, in the table's order. */
export const fitParametersOf = (law) => served.form.map((f) => f.flag).filter((flag) => (served.fit.by_law[law] || []).includes(flag));

/** A value as its field shows it: a plain number (n, T, the mechanical parts) to `digits`
 * significant digits, a physical one with its SI prefix (`11.5m`). */
export const fieldText = (flag, x, digits = 6) => (served.keys.get(flag)?.form === 'plain' ? num(x, digits) : siText(x));

/** A key's symbol (`U_t`) and the unit its field shows (`Ω`; none for a pure number). */
export function symbolAndUnit(flag) {
  const key = served.keys.get(flag);
  if (!key) return [flag, ''];
  const f = served.form.find((g) => g.flag === flag);
  return [key.symbol, key.unit === null || !f ? '' : f.unit];
}

const el = (tag, attributes = {}, children = []) => {
  const e = document.createElement(tag);
  for (const [name, value] of Object.entries(attributes)) e.setAttribute(name, value);
  e.append(...children);
  return e;
};

/** A symbol as the paper writes it: `_` opens a subscript that runs to a `(` or the end. */
export function symbolNodes(symbol) {
  const m = /^([^_]*)_([^(]*)(.*)$/.exec(symbol);
  if (!m) return [symbol];
  return [m[1], el('sub', {}, [m[2]]), m[3]].filter((n) => n !== '');
}

/** Build the form's fields from the answer of /api/keys; call it before anything reads them. */
export function buildForm(answer) {
  const keys = new Map(answer.keys.map((k) => [k.flag, k]));
  served.form = answer.form;
  served.keys = keys;
  served.fit = answer.fit;
  const fitSystems = $('#fit').dataset.forSystem.split(' ');
  for (const f of answer.form) {
    const key = keys.get(f.flag);
    const fieldset = $(`fieldset[data-for-system="${CSS.escape(f.fieldset)}"]:not(#fit)`);
    // A choice (the friction law) is a list of its names; a number a text field.
    const input = f.choices && f.choices.length
      ? el('select', { id: f.flag, name: f.flag, title: key.help }, f.choices.map((c) => new Option(c, c, c === f.value, c === f.value)))
      : el('input', { id: f.flag, name: f.flag, type: 'text', title: key.help });
    if (f.part) input.setAttribute('data-part', '');
    if (f.value !== null && input.tagName === 'INPUT') input.setAttribute('value', f.value);
    // A name's key has no symbol: its description's first words label it ("friction law").
    const text = key.symbol ? symbolNodes(key.symbol) : [key.description.split(/ of |:/)[0]];
    const children = [el('label', { for: f.flag }, text), input];
    if (f.unit) children.push(el('span', { class: 'unit' }, [f.unit]));
    const fits = answer.fit.parameters.includes(f.flag) && f.fieldset.split(' ').some((s) => fitSystems.includes(s));
    if (fits) {
      const laws = Object.keys(answer.fit.by_law).filter((law) => answer.fit.by_law[law].includes(f.flag));
      const box = el('input', { type: 'checkbox', name: `free-${f.flag}`, 'data-free': f.flag });
      if (laws.some((law) => (answer.fit.free[law] || []).includes(f.flag))) box.setAttribute('checked', '');
      children.push(el('label', { class: 'free', 'data-fit-laws': laws.join(' '), title: 'free in the fit: fitted to the record' }, [box, ' fit']));
    }
    children.push(el('span', { class: 'error', 'data-error-for': f.flag, role: 'alert' }));
    fieldset.append(el('div', f.law ? { class: 'field', 'data-law': f.law } : { class: 'field' }, children));
  }
  showLawFields();
}
