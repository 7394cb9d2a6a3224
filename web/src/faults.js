// SPDX-License-Identifier: MIT
// Hidden faults placed by clicking, as a fault scenario (docs/simulation.md): obstacles
// (transient or permanent) and danger spots at the clicked offset, dangerous passages at a
// clicked manhole (slots chosen in the list), malfunctions at a job number.

export const newFaults = () => ({ format: 'sewerplan-faults', version: 1, obstacles: [], danger: [], malfunctions: [] });

export const kFaultModes = ['obstacle-permanent', 'obstacle-transient', 'danger-spot', 'danger-passage'];

// A click in a fault mode on a pipe at `offset`, or on a manhole; whether it placed a fault.
export function clickFault(f, mode, { pipe, offset, manhole }) {
  if (mode === 'obstacle-permanent' && pipe) f.obstacles.push({ pipe, offset_m: offset, kind: 'permanent' });
  else if (mode === 'obstacle-transient' && pipe) f.obstacles.push({ pipe, offset_m: offset, kind: 'transient_lift' });
  else if (mode === 'danger-spot' && pipe) f.danger.push({ pipe, offset_m: offset });
  else if (mode === 'danger-passage' && manhole) f.danger.push({ manhole, from_slot: 1, to_slot: 2 });
  else return false;
  return true;
}

export const isEmpty = (f) => f.obstacles.length + f.danger.length + f.malfunctions.length === 0;

// The list of faults, each removable; a passage's slots editable.
export function renderFaults(list, f, onChange) {
  const rows = [];
  const row = (text, remove, extra = []) => {
    const li = document.createElement('li');
    li.append(text, ...extra);
    const b = Object.assign(document.createElement('button'), { textContent: '×', title: 'remove', className: 'small' });
    b.onclick = () => { remove(); onChange(); };
    li.append(b);
    rows.push(li);
  };
  const slot = (object, key) => {
    const input = Object.assign(document.createElement('input'), { type: 'number', min: 1, value: object[key], className: 'slot' });
    input.onchange = () => { object[key] = Number(input.value); onChange(); };
    return input;
  };
  f.obstacles.forEach((o, i) => row(`${o.kind} obstacle in ${o.pipe} at ${o.offset_m} m `, () => f.obstacles.splice(i, 1)));
  f.danger.forEach((d, i) => (d.manhole
    ? row(`dangerous passage in ${d.manhole}, slots `, () => f.danger.splice(i, 1), [slot(d, 'from_slot'), slot(d, 'to_slot')])
    : row(`danger spot in ${d.pipe} at ${d.offset_m} m `, () => f.danger.splice(i, 1))));
  f.malfunctions.forEach((m, i) => row(`${m.kind} malfunction at job ${m.at_job} `, () => f.malfunctions.splice(i, 1)));
  list.replaceChildren(...rows);
}
