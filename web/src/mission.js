// SPDX-License-Identifier: MIT
// The mission editor: clicks on the map become the CLI's mission JSON (docs/formats/mission-json.md),
// listed (each can be removed), downloaded and uploaded in exactly that format. The list has no
// up/down: the planner chooses the order of the tasks (the cheapest it finds, the paper's goal
// set), never the order they are listed in, so buttons that reorder them would promise what no
// plan does. The final task (the end) is always listed last, as it is done last.

export const newMission = (profile) =>
  ({ format: 'sewerplan-mission', version: 1, name: 'station', profile, tasks: [] });

const endIndex = (m) => {
  const i = m.tasks.findIndex((t) => t.final);
  return i < 0 ? m.tasks.length : i;
};

const uniqueName = (m, stem) => {
  let n = 1;
  while (m.tasks.some((t) => t.name === `${stem}-${n}`)) ++n;
  return `${stem}-${n}`;
};

// A click in `mode` on a pipe at `offset` (metres from its `from` end), or on a manhole.
// Returns whether the mission changed.
export function clickMission(m, mode, { pipe, offset, manhole }) {
  const place = manhole ? { manhole } : { pipe, offset_m: offset };
  if (mode === 'start') m.start = place;
  else if (mode === 'sample' && pipe) {
    m.tasks.splice(endIndex(m), 0, { name: uniqueName(m, 'sample'), type: 'take_water_sample', at: place });
  } else if (mode === 'inspect' && pipe) {
    m.tasks.splice(endIndex(m), 0, { name: uniqueName(m, 'inspect'), type: 'inspect_pipe', pipe });
  } else if (mode === 'goto') {
    m.tasks.splice(endIndex(m), 0, { name: uniqueName(m, 'goto'), type: 'go_to', at: place });
  } else if (mode === 'end') {
    // The end: anywhere in the clicked pipe (as the paper's "in P9"), or the clicked manhole.
    m.tasks = m.tasks.filter((t) => !t.final);
    m.tasks.push({ name: 'end', type: 'go_to', at: manhole ? { manhole } : { pipe }, final: true });
  } else {
    return false;
  }
  return true;
}

export const describePlace = (p) =>
  (p ? `${p.pipe ?? p.manhole ?? p.point}${p.offset_m !== undefined ? ` at ${p.offset_m} m` : ''}` : '—');

// The task list with its remove buttons; onChange() after every edit.
export function renderTasks(list, m, onChange, status = () => '') {
  list.replaceChildren(...m.tasks.map((t, i) => {
    const li = document.createElement('li');
    li.textContent = `${t.name}: ${t.type} ${t.pipe ?? describePlace(t.at)}${t.final ? ' (end)' : ''} ${status(t)}`;
    const button = (text, title, action) => {
      const b = document.createElement('button');
      Object.assign(b, { textContent: text, title, className: 'small' });
      b.onclick = () => { action(); onChange(); };
      li.append(b);
    };
    button('×', 'remove', () => m.tasks.splice(i, 1));
    return li;
  }));
}

// Saves a JSON document as a file download.
export function download(name, document_) {
  const url = URL.createObjectURL(new Blob([`${JSON.stringify(document_, null, 2)}\n`], { type: 'application/json' }));
  const a = Object.assign(document.createElement('a'), { href: url, download: name });
  a.click();
  URL.revokeObjectURL(url);
}
