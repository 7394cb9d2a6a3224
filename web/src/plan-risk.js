// SPDX-License-Identifier: MIT
// The plan's risk, next to the plan: with possible blockages weighed (risk mode "expected"), the
// chance that none on the route stops the robot and the expected cost of stops the planner chose
// the plan with, and the blockages the route passes; in the other modes, what the findings closed
// and that possible blockages were not weighed.
export function renderPlanRisk(element, result) {
  const r = result?.risk;
  element.replaceChildren();
  if (!r || (r.closed_by_findings === 0 && r.possible_blockages === 0 && r.unobstructed_probability === undefined)) {
    element.textContent = '';
    return;
  }
  const head = document.createElement('div');
  if (r.unobstructed_probability !== undefined) {
    head.textContent = `Risk: unobstructed run ${(100 * r.unobstructed_probability).toFixed(1)} %, ` +
      `expected cost of stops ${r.expected_cost_s.toFixed(1)} s; ${r.hazards.length} possible blockage` +
      `${r.hazards.length === 1 ? '' : 's'} on the route` + (r.note ? ` (${r.note})` : '');
  } else {
    head.textContent = `Risk (${r.mode}): ${r.closed_by_findings} places closed by findings; possible blockages not weighed` +
      ' (choose "weigh possible blockages" for the route\'s risk)';
  }
  element.append(head);
  if (r.hazards?.length) {
    const list = document.createElement('ul');
    list.append(...r.hazards.map((h) => {
      const li = document.createElement('li');
      li.textContent = `step ${h.step}: ${h.reason} in ${h.pipe} at ${h.offset_m.toFixed(2)} m, p ${h.probability.toFixed(2)}`;
      return li;
    }));
    element.append(list);
  }
}
