// SPDX-License-Identifier: MIT
// The scale bar: a bar of a round length (1, 2 or 5 times a power of ten metres) at most `maxPx`
// CSS pixels wide at the view's zoom (2^zoom pixels a metre: map-view.js's OrthographicView in the
// map's own metres), with its length written beside it.
//
//   scaleFor(3) -> {metres: 20, px: 160, text: '20 m'}   (at zoom 3 no wider than 160 px)

export function scaleFor(zoom, maxPx = 160) {
  const pxPerMetre = 2 ** zoom;
  const most = maxPx / pxPerMetre;  // the longest length that fits, metres
  const unit = 10 ** Math.floor(Math.log10(most));
  const metres = [5, 2, 1].map((k) => k * unit).find((m) => m <= most) ?? unit;
  const text = metres >= 1000 ? `${metres / 1000} km` : metres >= 1 ? `${metres} m` : `${Math.round(metres * 100)} cm`;
  return { metres, px: metres * pxPerMetre, text };
}

// Shows the scale of `zoom` in `bar` (its width) and `label` (its text).
export function showScale(bar, label, zoom) {
  const s = scaleFor(zoom);
  bar.style.width = `${s.px.toFixed(1)}px`;
  bar.dataset.metres = String(s.metres);
  label.textContent = s.text;
}
