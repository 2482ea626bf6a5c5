// Export: CSV of the displayed traces, PNG with a caption, the measurements as text.

import { $, $$, field, num, si } from './util.js';
import { state } from './state.js';
import { units } from './panels.js';
import { channelColumns, displayed, fftAxes, dbLevel } from './scope.js';

// ---------------------------------------------------------------- export
export function download(blob, name) {
  const url = URL.createObjectURL(blob);
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
}

/** The displayed traces as CSV (Y-T: the screen's samples; X-Y: the loop; FFT: the bars). */
export function csv() {
  const s = state.steady;
  const u = units();
  const lines = [];
  if (state.mode === 'fft') {
    const ax = fftAxes();
    const unit = { ch1: u.drive, ch2: u.position, ch3: u.velocity }[field('fft-source').value];
    const u2 = unit.replace('/', '_');
    lines.push(`harmonic,f_Hz,amplitude_peak_${u2},level_dB${u2}_rms,level_dB${u2}_peak`);
    for (const b of ax.bars) lines.push(`${b.k},${b.f},${b.a},${dbLevel(b.a, true)},${dbLevel(b.a, false)}`);
  } else {
    const names = channelColumns(s).names;
    const d = state.mode === 'xy'
      ? (state.trigger === 'transient' && state.transient ? channelColumns(state.transient) : channelColumns(s))
      : displayed();
    lines.push([names[0], names[3], names[1], names[2]].join(','));
    // Time from the first sample, as a scope's export counts it.
    const t0 = d.t.length ? d.t[0] : 0;
    for (let i = 0; i < d.t.length; i++) lines.push(`${d.t[i] - t0},${d.ch1[i]},${d.ch2[i]},${d.ch3[i]}`);
  }
  return `${lines.join('\n')}\n`;
}

export function fileStem() {
  const s = state.steady;
  const f = s.drive ? `${num(s.drive.f_Hz, 5)}Hz-${num(s.drive.amplitude, 4)}${units().drive}` : `w${s.w}-beta${s.beta}`;
  const view = state.mode === 'fft' ? 'fft' : `${state.mode}-${state.trigger === 'transient' ? 'transient' : 'steady'}`;
  return `stickslip-lab-${view}-${f}`;
}

/** The caption of an exported picture: the experiment in full, the drive, the result. */
export function captionText() {
  const s = state.steady;
  const u = units();
  const parts = [s.experiment];
  if (s.drive) parts.push(`drive f = ${si(s.drive.f_Hz, 'Hz', 6)}, amplitude ${si(s.drive.amplitude, u.drive, 5)}`);
  parts.push(`w = Ω/ω0 = ${num(s.w, 6)}, β = ${num(s.beta, 6)}`);
  parts.push(`class ${s.class}, gain G = ${num(s.gain, 6)}, ${s.stops_per_period} stops per period`);
  parts.push(`view ${state.mode === 'fft' ? `FFT (${field('fft-scale').value})` : state.mode}, ${state.trigger}; stickslip lab`);
  return parts.join('; ');
}

/** `text` broken into lines of at most `width` pixels in the context's font. */
export function wrapText(g, text, width) {
  const lines = [];
  let line = '';
  for (const word of text.split(' ')) {
    const next = line ? `${line} ${word}` : word;
    if (line && g.measureText(next).width > width) {
      lines.push(line);
      line = word;
    } else {
      line = next;
    }
  }
  if (line) lines.push(line);
  return lines;
}

export function exportPng() {
  const screen = $('#screen');
  const ratio = screen.width / (screen.clientWidth || screen.width) || 1;
  const measure = document.createElement('canvas').getContext('2d');
  measure.font = '12px system-ui, sans-serif';
  const cssWidth = screen.width / ratio;
  const lines = wrapText(measure, captionText(), cssWidth - 16);
  const out = document.createElement('canvas');
  out.width = screen.width;
  out.height = screen.height + Math.round((10 + 16 * lines.length) * ratio);
  const g = out.getContext('2d');
  g.fillStyle = '#ffffff';
  g.fillRect(0, 0, out.width, out.height);
  g.drawImage(screen, 0, 0);
  g.scale(ratio, ratio);
  g.font = '12px system-ui, sans-serif';
  g.fillStyle = '#222';
  lines.forEach((line, k) => g.fillText(line, 8, screen.height / ratio + 16 + 16 * k));
  window.stickslipLab.lastCaption = lines;
  out.toBlob((blob) => download(blob, `${fileStem()}.png`), 'image/png');
}

/** The measurements table as tab-separated text (pasted into a spreadsheet or a report). */
export function measurementsTsv() {
  const rows = [];
  const table = $('#measurements table');
  for (const tr of $$('tr', table)) {
    const cells = Array.from(tr.children, (c) => c.textContent.replace(/\s+/g, ' ').replace(/ \?$/, '').trim());
    // The line under the class (the rule of a static motion): a row of its own, when shown.
    if (tr.classList.contains('note-row')) {
      if (cells[0]) rows.push(`class rule\t${cells[0]}`);
      continue;
    }
    rows.push(cells.join('\t'));
  }
  if (state.steady) rows.unshift(`experiment\t${captionText()}`);
  return `${rows.join('\n')}\n`;
}

export async function copyMeasurements() {
  const text = measurementsTsv();
  window.stickslipLab.lastCopied = text;
  const out = $('[data-copy="status"]');
  try {
    await navigator.clipboard.writeText(text);
    out.textContent = 'copied: paste into a spreadsheet or a report';
  } catch (e) {
    // Without clipboard permission: select the text for Ctrl-C.
    const area = document.createElement('textarea');
    area.value = text;
    document.body.append(area);
    area.select();
    const ok = document.execCommand && document.execCommand('copy');
    area.remove();
    out.textContent = ok ? 'copied: paste into a spreadsheet or a report' : 'the browser refused the clipboard';
  }
}
