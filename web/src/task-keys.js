// SPDX-License-Identifier: MIT
// The mission's task list as a GIS editor's selection, and the editor's keys. A click on a task in
// the list selects it (its buttons aside); a task just added on the map is selected. The Delete (or
// Backspace) key removes the selected task; Ctrl+Z undoes the last edit of the mission, Ctrl+Y and
// Ctrl+Shift+Z redo it (undo.js); Home fits the network to the view. Keys typed into a text field
// or a selector are theirs, not the editor's.
//
//   const selection = new TaskSelection(list, () => state.mission.tasks);
//   bindEditorKeys({ undo, redo, remove: () => selection.remove(...), fit });

export class TaskSelection {
  constructor(list, tasks) {
    this.list = list;
    this.tasks = tasks;
    this.name = null;
    this.known = null;  // the task names the list showed last
    list.addEventListener('click', (e) => {
      if (e.target.closest('button')) return;
      const li = e.target.closest('li');
      if (!li) return;
      const i = [...list.children].indexOf(li);
      this.name = this.tasks()[i]?.name ?? null;
      this.mark();
    });
    // renderTasks (mission.js) replaces the list's items after every change: mark them again.
    new MutationObserver(() => this.mark()).observe(list, { childList: true });
  }

  // Marks the selected task's item; a task that appeared alone since the last time is selected.
  mark() {
    const names = this.tasks().map((t) => t.name);
    if (this.known) {
      const added = names.filter((n) => !this.known.has(n));
      if (added.length === 1) this.name = added[0];
    }
    this.known = new Set(names);
    if (!this.known.has(this.name)) this.name = null;
    [...this.list.children].forEach((li, i) => li.classList.toggle('selected', names[i] === this.name));
  }

  // The selected task's index in the mission, or -1.
  index() { return this.name === null ? -1 : this.tasks().findIndex((t) => t.name === this.name); }

  // Forgets the tasks seen (another map's mission: none of its tasks is "added").
  reset() { this.known = null; this.name = null; }
}

const typing = (t) => t instanceof HTMLElement && (t.isContentEditable || t.tagName === 'TEXTAREA' || t.tagName === 'SELECT' ||
  (t.tagName === 'INPUT' && !['radio', 'checkbox', 'button', 'file', 'range'].includes(t.type)));

export function bindEditorKeys({ undo, redo, remove, fit }) {
  document.addEventListener('keydown', (e) => {
    if (typing(e.target)) return;
    const ctrl = e.ctrlKey || e.metaKey, key = e.key.toLowerCase();
    let done = true;
    if (ctrl && key === 'z' && !e.shiftKey) undo();
    else if (ctrl && (key === 'y' || (key === 'z' && e.shiftKey))) redo();
    else if (!ctrl && (e.key === 'Delete' || e.key === 'Backspace')) done = remove();
    else if (!ctrl && e.key === 'Home') fit();
    else done = false;
    if (done) e.preventDefault();
  });
}
