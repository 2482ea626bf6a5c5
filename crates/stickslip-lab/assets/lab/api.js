// The lab's JSON API (docs/lab.md): one GET per answer, one request per slot at a time.

import { $, field } from './util.js';

// ---------------------------------------------------------------- the API
export class ApiFailure extends Error {
  constructor(status, message, field) {
    super(message);
    this.status = status;
    this.field = field;
  }
}

/** GET /api/<name>?<params> (POST with a body); the JSON answer, or an ApiFailure with the
 * server's line. */
// The page's own name for the server's fair queues (one per open page, not stored).
export const CLIENT_ID = Array.from(crypto.getRandomValues(new Uint8Array(12)), (b) => b.toString(16).padStart(2, '0')).join('');
export async function api(name, params, signal, upload = null) {
  const init = { signal, headers: { 'X-Lab-Client': CLIENT_ID } };
  if (upload !== null) {
    // POST /api/record and /api/fit: { body, type }, a scope record's CSV text or JSON files.
    init.method = 'POST';
    init.headers['Content-Type'] = upload.type;
    init.body = upload.body;
  }
  let response;
  try {
    response = await fetch(`/api/${name}?${params}`, init);
  } catch (e) {
    if (isAbort(e)) throw e;
    // The browser's own words for a server that is gone ("Failed to fetch") say nothing.
    throw new ApiFailure(0, NOT_ANSWERING);
  }
  let body = null;
  try {
    body = await response.json();
  } catch (e) {
    throw new ApiFailure(response.status, `the server answered ${response.status} without JSON`);
  }
  if (!response.ok) throw new ApiFailure(response.status, body.error || `error ${response.status}`, body.field);
  return body;
}

/** What the page says when the lab's server does not answer at all. */
export const NOT_ANSWERING = "the lab's server is not answering: is stickslip lab still running on the computer that serves this page? Start it again, then reload the page";

/** One request per slot at a time: a new one aborts the one before (a stale answer is dropped). */
export const slots = {};
export async function latest(slot, name, params, upload = null) {
  if (slots[slot]) slots[slot].abort();
  const controller = new AbortController();
  slots[slot] = controller;
  try {
    return await api(name, params, controller.signal, upload);
  } finally {
    if (slots[slot] === controller) delete slots[slot];
  }
}
export const isAbort = (e) => e && e.name === 'AbortError';
