// SPDX-License-Identifier: MIT
// Undo and redo of the mission's edits: each state of the mission the editor reached, as its JSON
// text (a snapshot is a value: a later edit in place cannot change it). main.js records one after
// every edit (a click on the map, a task moved or removed, a mission uploaded); recording the state
// already present is no change, so restoring a snapshot and re-rendering it records nothing and
// keeps the redo list. A new edit after an undo drops what could be redone, as in every editor.
// A map opened starts a new history: its missions name its own pipes.
//
//   const history = new EditHistory();
//   history.reset(JSON.stringify(mission));
//   history.record(JSON.stringify(edited));   // true: a new state
//   mission = JSON.parse(history.undo());     // null when there is nothing to undo
export class EditHistory {
  constructor(limit = 200) {
    this.limit = limit;  // the oldest states are forgotten beyond it
    this.past = [];
    this.future = [];
    this.present = null;
  }

  reset(snapshot) {
    this.past = [];
    this.future = [];
    this.present = snapshot;
  }

  // Records `snapshot` as the state after an edit; returns whether it differs from the present.
  record(snapshot) {
    if (snapshot === this.present) return false;
    if (this.present !== null) this.past.push(this.present);
    if (this.past.length > this.limit) this.past.shift();
    this.present = snapshot;
    this.future = [];
    return true;
  }

  get canUndo() { return this.past.length > 0; }
  get canRedo() { return this.future.length > 0; }

  // The state before the present (which becomes redoable), or null.
  undo() {
    if (!this.canUndo) return null;
    this.future.push(this.present);
    this.present = this.past.pop();
    return this.present;
  }

  // The state undone last, or null.
  redo() {
    if (!this.canRedo) return null;
    this.past.push(this.present);
    this.present = this.future.pop();
    return this.present;
  }
}
