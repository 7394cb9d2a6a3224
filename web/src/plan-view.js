// SPDX-License-Identifier: MIT
// The plan view: a plan's summary (steps, cost, time, energy, the decision, whether a motion
// table was used, what the map's findings closed), its steps in the paper's vocabulary (hover one for its fused action), and
// the dropped tasks with their reasons.
const $ = (id) => document.getElementById(id);

export function renderPlan(result) {
  $('plan-summary').textContent =
    `${result.steps.length} steps, ${result.cost_s.toFixed(1)} s, ${result.energy_wh.toFixed(1)} Wh; ` +
    `${result.decision}; ${result.algorithm}; ${result.motion_table ? 'motion table' : 'no motion table'}` +
    (result.risk?.closed_by_findings ? `; ${result.risk.closed_by_findings} places closed by findings` : '') +
    (result.risk?.possible_blockages ? `; ${result.risk.possible_blockages} possible blockages weighed` : '');
  $('steps').replaceChildren(...result.steps.map((s, i) => {
    const li = document.createElement('li');
    li.textContent = s.action;
    li.title = result.fused[i]?.text ?? '';
    return li;
  }));
  $('dropped').replaceChildren(...result.dropped.map((d) => {
    const li = document.createElement('li');
    li.textContent = `${d.task}: ${d.reason}`;
    return li;
  }));
}
