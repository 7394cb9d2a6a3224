// SPDX-License-Identifier: MIT
// What a run's end says on screen: how it ended and what it achieved. "Ended" alone is wrong for
// a run whose robot reached the end but dropped every task on the way, so the line says how many
// of the mission's tasks were done and which were dropped; its class ('ended', 'partial',
// 'nothing-done', 'beacon', 'halted') colours it.
//
//   const { text, className } = outcomeLine(missionEndEvent, mission, droppedTaskNames);

// `e`: the mission_end event ({outcome, end, tasks_done}); `mission`: the mission run (its tasks,
// the final one among them); `dropped`: the tasks dropped during the run.
export function outcomeLine(e, mission, dropped) {
  const finals = new Set((mission?.tasks ?? []).filter((t) => t.final).map((t) => t.name));
  const work = (mission?.tasks ?? []).filter((t) => !t.final).map((t) => t.name);
  const done = e.tasks_done.filter((t) => !finals.has(t));
  const lost = [...dropped].filter((t) => !finals.has(t));
  // A run replayed from a log may not match the mission being edited: count what the run says.
  const total = Math.max(work.length, done.length + lost.length);
  const head = e.outcome === 'ended' ? `Ended: ${e.end} reached`
    : e.outcome === 'beacon' ? `Beacon on: ${e.end}` : `Halted: ${e.end}`;
  const tally = total === 0 ? '' : done.length === 0
    ? `, but no task done${lost.length ? ` (${lost.length === total ? 'all ' : ''}${lost.length} dropped: ${lost.join(', ')})` : ''}`
    : `; ${done.length} of ${total} tasks done${lost.length ? `, ${lost.length} dropped: ${lost.join(', ')}` : ''}`;
  const className = e.outcome !== 'ended' ? e.outcome
    : total > 0 && done.length === 0 ? 'nothing-done' : lost.length > 0 ? 'partial' : 'ended';
  return { text: `${head}${tally}`, className };
}
