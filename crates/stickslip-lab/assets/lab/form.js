// The form of the model's values, built from the server's key table (/api/keys): one field
// per key of `form`, in the table's order, in the fieldset for the systems it is shown for,
// labelled with the key's symbol, titled with its help; a "fit" box on the values a fit of
// a circuit may free (`fit.parameters`), ticked on those it frees by default (`fit.free`).

import { $ } from './util.js';

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
  const fitSystems = $('#fit').dataset.forSystem.split(' ');
  for (const f of answer.form) {
    const key = keys.get(f.flag);
    const fieldset = $(`fieldset[data-for-system="${CSS.escape(f.fieldset)}"]:not(#fit)`);
    const input = el('input', { id: f.flag, name: f.flag, type: 'text', title: key.help });
    if (f.part) input.setAttribute('data-part', '');
    if (f.value !== null) input.setAttribute('value', f.value);
    const children = [el('label', { for: f.flag }, symbolNodes(key.symbol)), input];
    if (f.unit) children.push(el('span', { class: 'unit' }, [f.unit]));
    const fits = answer.fit.parameters.includes(f.flag) && f.fieldset.split(' ').some((s) => fitSystems.includes(s));
    if (fits) {
      const box = el('input', { type: 'checkbox', name: `free-${f.flag}`, 'data-free': f.flag });
      if (answer.fit.free.includes(f.flag)) box.setAttribute('checked', '');
      children.push(el('label', { class: 'free', title: 'free in the fit: fitted to the record' }, [box, ' fit']));
    }
    children.push(el('span', { class: 'error', 'data-error-for': f.flag, role: 'alert' }));
    fieldset.append(el('div', { class: 'field' }, children));
  }
}
