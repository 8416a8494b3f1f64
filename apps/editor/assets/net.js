// Talking to the tvf server: the binary mesh and field frames, and an edit queue that keeps at
// most one request in flight and merges consecutive drags of the same constraint.

export const FIELD_MAGIC = 0x46465654; // "TVFF" little-endian

// A field frame: u32 magic, u32 json length, the status JSON (UTF-8) padded with spaces to a
// multiple of 4 bytes, then f32 coordinates, 2 per face in the face frames.
export function parseFieldFrame(buffer) {
  const head = new Uint32Array(buffer, 0, 2);
  if (head[0] !== FIELD_MAGIC) throw new Error('field payload: bad magic number');
  const jsonLength = head[1];
  const status = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 8, jsonLength)));
  const offset = 8 + Math.ceil(jsonLength / 4) * 4;
  const coords = new Float32Array(buffer, offset, (buffer.byteLength - offset) / 4);
  return { status, coords };
}

// The session token the server embedded in the page; every API call carries it.
export const TOKEN = document.querySelector('meta[name="tvf-token"]').content;

// fetch() of an API path with the session token.
export function apiFetch(path, options = {}) {
  return fetch(path, { cache: 'no-store', ...options, headers: { ...(options.headers || {}), 'X-TVF-Token': TOKEN } });
}

async function errorText(response) {
  const text = await response.text();
  try { return JSON.parse(text).error || text; } catch (_) { return text || response.statusText; }
}

export async function getBinary(path) {
  const response = await apiFetch(path);
  if (!response.ok) throw new Error(`${path}: ${response.status} ${await errorText(response)}`);
  return response.arrayBuffer();
}

export class EditQueue {
  // onField({status, coords}, milliseconds) after every accepted edit; onError(message, op) on a
  // rejected edit or a lost connection; onIdle() when the queue runs empty.
  constructor(onField, onError, onIdle) {
    this.queue = [];
    this.busy = false;
    this.onField = onField;
    this.onError = onError;
    this.onIdle = onIdle;
  }

  // Queues an edit; a 'set' directly following a queued 'set' of the same id replaces it.
  push(op) {
    const last = this.queue[this.queue.length - 1];
    const mergeable = (a, b) => a && a.op === b.op && (
      (a.op === 'set' && a.constraint.id === b.constraint.id) || a.op === 'omega' || a.op === 'basis_size');
    if (mergeable(last, op)) this.queue[this.queue.length - 1] = op; else this.queue.push(op);
    if (!this.busy) this.next();
  }

  async next() {
    const op = this.queue.shift();
    if (!op) { this.busy = false; this.onIdle(); return; }
    this.busy = true;
    const started = performance.now();
    try {
      const response = await apiFetch('/api/edit', {
        method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(op),
      });
      if (response.ok) {
        this.onField(parseFieldFrame(await response.arrayBuffer()), performance.now() - started);
      } else {
        const message = `${op.op} rejected (${response.status}): ${await errorText(response)}`;
        if (op.op === 'add') {
          // Edits queued for a constraint that was never added would only fail too.
          this.queue = this.queue.filter((o) => !(o.constraint && o.constraint.id === op.constraint.id));
        }
        this.onError(message, op);
      }
    } catch (e) {
      this.onError(`lost connection to the tvf server (${e.message})`);
    }
    this.next();
  }
}
