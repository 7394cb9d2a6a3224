// SPDX-License-Identifier: MIT
// The coordinates under the pointer in the map's coordinate reference system: the map view draws
// the map's own x and y (metres, map-view.js), so the point under the pointer, unprojected by the
// view, is in the map's CRS as it is, the one `GET /api/maps` names ("crs", core/crs.h); no
// transformation. A map that names none has local coordinates, and the line says so.
//
//   trackCursor(viewElement, view, line, () => crsOfTheOpenMap);

// x and y to the centimetre (a survey's precision), with the CRS or "local".
export function formatCoordinates([x, y], crs) {
  return `x ${x.toFixed(2)}, y ${y.toFixed(2)} ${crs ?? '(local metres: the map names no CRS)'}`;
}

export function trackCursor(element, view, line, crs) {
  element.addEventListener('pointermove', (e) => {
    const viewport = view.deck.getViewports()[0];
    if (!viewport) return;
    const box = element.getBoundingClientRect();
    const at = viewport.unproject([e.clientX - box.left, e.clientY - box.top]);
    line.textContent = formatCoordinates(at, crs());
    line.dataset.x = String(at[0]);
    line.dataset.y = String(at[1]);
  });
  element.addEventListener('pointerleave', () => { line.textContent = ''; });
}
