// SPDX-License-Identifier: MIT
// The Plan panel's subject: which plan is on screen. A plan asked with the Plan button is one
// plan; a simulation or a replay has the first plan and each replan after it, each with its
// reason, its steps and its route. The panel lists them all (the latest is the robot's current
// plan), and shows the one chosen: its summary, steps and dropped tasks (plan-view.js for a plan
// of the Plan button), its route highlighted on the map. A failed plan, another map or mission
// clears it: what is shown is never an earlier plan's.
//
//   const plans = new PlanHistory({ onChange: draw });
//   plans.planned(result);           // the Plan button's answer
//   plans.event('replan', e);        // a simulation's plan or replan event
//   plans.route(e);                  // the route that follows it ({steps, pipes})
import { renderPlan } from './plan-view.js';

const $ = (id) => document.getElementById(id);
const fmt = (t) => `${(t ?? 0).toFixed(1)} s`;

export class PlanHistory {
  constructor({ onChange }) {
    this.onChange = onChange;
    this.clear();
  }

  // Nothing planned (another map, another mission, a plan that failed: `why` says so).
  clear(why = '') {
    this.plans = [];
    this.shown = -1;
    this.follow = true;  // show each new plan as it comes, until the operator chooses one
    this.reasons = new Map();  // task -> why it was dropped, from the run's task_dropped events
    this.render(why);
  }

  // The Plan button's plan (plan --json's document).
  planned(result) {
    this.clear();
    this.plans.push({ result, pipes: null });
    this.shown = 0;
    this.render();
  }

  // A run's plan or replan event; its steps and route come with the route event after it.
  event(type, e) {
    this.plans.push({ type, e, steps: [], pipes: null });
    if (this.follow) this.shown = this.plans.length - 1;
    this.render();
  }

  route(e, pipes) {
    const last = this.plans.at(-1);
    if (!last || last.result) return;
    last.steps = e.steps ?? [];
    last.pipes = pipes;
    this.render();
  }

  dropped(task, reason) {
    this.reasons.set(task, reason);
    this.render();
  }

  // The operator's choice in the list: that plan shown, its route highlighted.
  choose(i) {
    this.shown = i;
    this.follow = i === this.plans.length - 1;
    this.render();
    this.onChange();
  }

  // The route of the plan shown when it is not the current one (an old plan chosen), else null.
  highlighted() {
    const p = this.plans[this.shown];
    return p && this.shown !== this.plans.length - 1 && p.pipes ? { pipes: [...p.pipes] } : null;
  }

  render(why = '') {
    const list = $('plans');
    const runPlans = this.plans.filter((p) => !p.result);
    list.replaceChildren(...runPlans.map((p, i) => {
      const li = document.createElement('li');
      const e = p.e;
      const current = i === this.plans.length - 1;
      li.textContent = `${fmt(e.t_s)} ${e.type === 'replan' ? 'replan' : 'plan'}: ${e.reason} → ${e.decision}, ` +
        `${e.steps} steps${e.dropped.length ? `, drops ${e.dropped.join(', ')}` : ''}${current ? ' (current)' : ' (old route)'}`;
      li.className = `${e.type}${i === this.shown ? ' shown' : ''}`;
      li.tabIndex = 0;
      li.onclick = () => this.choose(i);
      li.onkeydown = (k) => { if (k.key === 'Enter' || k.key === ' ') this.choose(i); };
      return li;
    }));
    const p = this.plans[this.shown];
    if (!p) {
      $('plan-summary').textContent = why;
      $('plan-summary').className = why ? 'failed' : '';
      $('steps').replaceChildren();
      $('dropped').replaceChildren();
      return;
    }
    $('plan-summary').className = '';
    if (p.result) {
      renderPlan(p.result);
      return;
    }
    const e = p.e;
    $('plan-summary').textContent =
      `${this.shown === this.plans.length - 1 ? 'Current plan' : 'Old plan'} (${e.type} at ${fmt(e.t_s)}: ${e.reason}): ` +
      `${e.steps} steps${e.cost_s !== undefined ? `, ${e.cost_s.toFixed(1)} s` : ''}; ${e.decision}; ends ${e.end}`;
    $('steps').replaceChildren(...p.steps.map((s) => Object.assign(document.createElement('li'), { textContent: s })));
    $('dropped').replaceChildren(...e.dropped.map((task) => Object.assign(document.createElement('li'), {
      textContent: `${task}: ${this.reasons.get(task) ?? 'dropped'}`,
    })));
  }
}
