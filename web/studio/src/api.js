// The studio's JSON API as its pages call it: a GET, or a POST of JSON
// (or of raw bytes, an upload); the status and the body, parsed when it
// is JSON.
export async function api(path, body, raw) {
  const init = body === undefined ? {} : raw
    ? { method: "POST", body }
    : { method: "POST", headers: { "Content-Type": "application/json" }, body: JSON.stringify(body) };
  const r = await fetch(path, init);
  const type = r.headers.get("Content-Type") || "";
  return { status: r.status, data: type.includes("json") ? await r.json() : await r.text() };
}
