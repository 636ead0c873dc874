// The studio's HTTP API (docs/studio.md): JSON in, JSON out. A refusal rejects with an Error
// carrying the server's message, the field it names and the status.

export class RequestError extends Error {
  constructor(body, status) {
    super(body && body.error ? body.error : `request failed (${status})`);
    this.field = body ? body.field : '';
    this.status = status;
  }
}

// The time the server spent on the request (its Server-Timing header), in ms, or NaN.
function serverTime(response) {
  const timing = response.headers.get('Server-Timing') || '';
  const match = /dur=([0-9.]+)/.exec(timing);
  return match ? Number(match[1]) : NaN;
}

async function answer(response) {
  const text = await response.text();
  let body = null;
  try {
    body = JSON.parse(text);
  } catch {
    body = null;
  }
  if (!response.ok) throw new RequestError(body, response.status);
  Object.defineProperty(body, 'serverMs', { value: serverTime(response), enumerable: false });
  return body;
}

export async function get(path) {
  return answer(await fetch(path, { cache: 'no-store' }));
}

export async function post(path, request = {}) {
  return answer(await fetch(path, {
    method: 'POST',
    headers: { 'Content-Type': 'application/json' },
    body: JSON.stringify(request),
  }));
}
