// SPDX-License-Identifier: MIT
// The latest request only: answers that may come out of order (a map's driveability asked for one
// profile, then for another, or for the next map opened) are used only if no request of the same
// kind was started after theirs; an older one's answer, or its error, is dropped. Pure: no DOM, so
// web/test checks it in plain node.
export function latestOnly() {
  let last = 0;
  return {
    // Starts tracking `promise` as the latest request. Resolves with {value, latest} when it
    // answers while still the latest (latest(): whether it still is, for work done after), with
    // null when a later request was started or drop() was called meanwhile; rejects with its
    // error only while it is the latest.
    async run(promise) {
      const n = ++last;
      try {
        const value = await promise;
        return n === last ? { value, latest: () => n === last } : null;
      } catch (e) {
        if (n !== last) return null;
        throw e;
      }
    },
    // Drops every request under way (their answers resolve to null).
    drop() { ++last; },
  };
}
