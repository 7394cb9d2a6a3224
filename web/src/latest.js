// SPDX-License-Identifier: MIT
// Requests about the open map (its driveability for the selected profile) whose answers may come
// out of order: a request is for the map being opened, or open (the one last passed to opening(),
// known before its geometry is read), and its answer is used only once that map has been drawn
// and if no later request was started and no other map opened meanwhile; an older one's answer,
// or its error, is dropped, and the request itself aborted (its AbortSignal), so the server's
// answer is not downloaded and read in vain. Pure: no DOM, so web/test checks it in plain node.
export function mapRequests() {
  let last = 0, map = null;  // map: {id, drawn (a promise)}
  let pending = null;        // the AbortController of the latest request, until another replaces it
  const dropPending = () => { pending?.abort(); pending = null; };
  return {
    // The map `id` is being opened: later requests are for it, earlier ones dropped. Returns the
    // function to call once it is drawn (until then its requests' answers wait).
    opening(id) {
      dropPending();
      let drawn;
      map = { id, drawn: new Promise((resolve) => { drawn = resolve; }) };
      return drawn;
    },
    // The map being opened or open (null before the first).
    get id() { return map?.id ?? null; },
    // Asks ask(id, signal) for that map; `signal` (an AbortSignal) aborts when a later request
    // starts or another map opens. Resolves with {id, value, latest} once the map is drawn, if this
    // is still the latest request for the current map (latest(): whether it still is, for work
    // done after, such as reading the answer's body), else with null; rejects with its error under
    // the same condition.
    async run(ask) {
      dropPending();
      const n = ++last, m = map, controller = new AbortController();
      pending = controller;
      const latest = () => n === last && m === map;
      let value, error = null;
      try {
        value = await ask(m.id, controller.signal);
      } catch (e) {
        error = e;
      }
      if (!latest()) return null;
      await m.drawn;
      if (!latest()) return null;
      if (error) throw error;
      return { id: m.id, value, latest };
    },
  };
}
