// SPDX-License-Identifier: MIT
// The campaign panel: a fault campaign on the open map and mission, run by the server's campaign
// library as `sewerplan campaign` runs it (docs/campaign.md): the form (runs, seed, fault rates,
// jobs, push, the planner's time limit, risk, obstacles from the map's condition data), the progress streamed run by run with a cancel button, the summary as charts (the
// figures of summary.md: outcomes, tasks against the oracle and the baseline, beacons by cause),
// drawn as plain SVG, and the table of runs, where a click opens the run in the replay view.
import * as api from './api.js';

const SVG = 'http://www.w3.org/2000/svg';
const OUTCOMES = ['exit', 'end_point', 'beacon', 'stranded'];
const COLOURS = { oracle: '#2ca02c', ours: '#1f77b4', baseline: '#ff7f0e' };
const MAX_ROWS = 1000;  // the table's rows at most; any run opens by its number too

function svg(tag, attributes = {}, text = null) {
  const e = document.createElementNS(SVG, tag);
  for (const [k, v] of Object.entries(attributes)) e.setAttribute(k, v);
  if (text !== null) e.textContent = text;
  return e;
}

// A grouped bar chart: for each category, one bar per series ({name, colour, values[]}), the
// value above it and in its tooltip. Plain SVG, 300 px wide.
export function barChart({ id, title, categories, series, format = (v) => String(v) }) {
  const width = 300;
  const height = 150;
  const [left, top, bottom] = [8, 30, 22];
  const max = Math.max(1e-9, ...series.flatMap((s) => s.values));
  const group = (width - 2 * left) / categories.length;
  const bar = Math.min(28, (group - 6) / series.length);
  const chart = svg('svg', { id, class: 'chart', width, height, viewBox: `0 0 ${width} ${height}` });
  chart.append(svg('text', { x: left, y: 12, class: 'title' }, title));
  series.forEach((s, k) => {
    chart.append(svg('rect', { x: left + k * 80, y: 17, width: 9, height: 9, fill: s.colour }));
    chart.append(svg('text', { x: left + k * 80 + 12, y: 25 }, s.name));
  });
  const base = height - bottom;
  categories.forEach((category, c) => {
    const x0 = left + c * group + (group - bar * series.length) / 2;
    series.forEach((s, k) => {
      const v = s.values[c] ?? 0;
      const h = (v / max) * (base - top - 12);
      const rect = svg('rect', { x: x0 + k * bar, y: base - h, width: bar - 1, height: h, fill: s.colour,
                                 'data-series': s.name, 'data-category': category, 'data-value': v });
      rect.append(svg('title', {}, `${s.name}, ${category}: ${format(v)}`));
      chart.append(rect);
      chart.append(svg('text', { x: x0 + k * bar + bar / 2, y: base - h - 2, class: 'value' }, format(v)));
    });
    chart.append(svg('text', { x: left + c * group + group / 2, y: base + 12, class: 'category' }, category));
  });
  chart.append(svg('line', { x1: left, x2: width - left, y1: base, y2: base, stroke: '#444' }));
  return chart;
}

// The charts of a summary.json document (the campaign library's).
export function summaryCharts(s) {
  const both = (f) => [{ name: 'ours', colour: COLOURS.ours, values: f(s.ours) },
                       { name: 'baseline', colour: COLOURS.baseline, values: f(s.baseline) }];
  const causes = Object.keys(s.ours.beacons_by_cause);
  const bins = [...Array(10).keys()].map((b) => `${b * 10}-`).concat(['100%', 'more']);
  const fixed = (v) => v.toFixed(2);
  return [
    barChart({ id: 'chart-outcomes', title: `How the ${s.completed} runs ended`,
               categories: OUTCOMES.map((o) => o.replace('_', ' ')),
               series: both((p) => OUTCOMES.map((o) => p.outcomes[o])) }),
    barChart({ id: 'chart-tasks', title: 'Tasks done per run (mean)',
               categories: ['mean tasks done'], format: fixed,
               series: [{ name: 'oracle', colour: COLOURS.oracle, values: [s.oracle_tasks_mean] },
                        ...both((p) => [p.tasks_mean])] }),
    barChart({ id: 'chart-vs-oracle', title: 'Runs by their share of the oracle\'s tasks',
               categories: bins, series: both((p) => p.tasks_vs_oracle_histogram) }),
    barChart({ id: 'chart-beacons', title: 'Beacons by cause',
               categories: causes.map((c) => c.replaceAll('_', ' ')),
               series: both((p) => causes.map((c) => p.beacons_by_cause[c])) }),
  ];
}

const pct = (v) => `${(100 * v).toFixed(1)} %`;

export class CampaignPanel {
  // $: the page's element lookup; mapId() and mission(): what the campaign runs on;
  // onOpenRun(index, events): a run's events for the replay view; onError(message).
  constructor($, { mapId, mission, onOpenRun, onError }) {
    Object.assign(this, { $, mapId, mission, onOpenRun, onError });
    this.running = null;
    this.progressSeen = 0;
    this.summary = null;
    $('campaign-start').onclick = () => this.start();
    $('campaign-cancel').onclick = () => this.cancel();
    $('campaign-open').onclick = () => this.open(Number($('campaign-open-run').value));
  }

  request() {
    const $ = this.$;
    const body = { mission: this.mission(), runs: Number($('campaign-runs').value),
                   seed: $('campaign-seed').value.trim() || '1', jobs: Number($('campaign-jobs').value),
                   allow_push: $('campaign-push').checked,
                   planner_time_limit_s: Number($('campaign-planner-limit').value || 0),
                   risk: $('campaign-risk').value,
                   faults_from_condition: $('campaign-faults-from-condition').checked };
    const rates = $('campaign-rates').value.trim();
    if (rates) body.fault_rates = rates;
    return body;
  }

  async start() {
    const $ = this.$;
    this.onError('');
    this.running?.abort();
    this.running = new AbortController();
    this.progressSeen = 0;
    this.summary = null;
    $('campaign-charts').replaceChildren();
    $('campaign-table').replaceChildren();
    $('campaign-start').disabled = true;
    $('campaign-cancel').disabled = false;
    try {
      await api.campaign(this.mapId(), this.request(), (type, data) => this.onEvent(type, data), this.running.signal);
    } catch (e) {
      if (e.name !== 'AbortError') this.onError(e.message);
    } finally {
      $('campaign-start').disabled = false;
      $('campaign-cancel').disabled = true;
    }
  }

  // The server stops the campaign; its stream then ends with the summary of the runs done.
  async cancel() {
    try {
      await api.cancelCampaign();
    } catch (e) {
      this.onError(e.message);
    }
  }

  onEvent(type, data) {
    const $ = this.$;
    if (type === 'start') {
      $('campaign-progress').max = data.total;
      $('campaign-progress').value = 0;
      const jobs = data.jobs === data.jobs_requested ? `${data.jobs} at a time` : `${data.jobs} at a time, of ${data.jobs_requested} asked`;
      $('campaign-status').textContent = `0/${data.total} runs (${jobs}), faults ${data.fault_rates}, risk ${data.risk}`;
    } else if (type === 'progress') {
      this.progressSeen += 1;
      $('campaign-progress').max = data.total;
      $('campaign-progress').value = data.done;
      const o = data.outcomes;
      $('campaign-status').textContent = `${data.done}/${data.total} runs, ${data.failed} crashed or hung, ` +
        `${data.elapsed_s.toFixed(1)} s; ours: ${o.exit} exit, ${o.end_point} end point, ${o.beacon} beacon, ` +
        `${o.stranded} stranded; ${data.tasks} tasks of the oracle's ${data.oracle_tasks}`;
    } else if (type === 'summary') {
      this.show(data);
    } else if (type === 'error') {
      $('campaign-status').textContent = data.error.message;
    }
  }

  show(done) {
    const $ = this.$;
    this.summary = done;
    const s = done.summary;
    $('campaign-progress').value = s.runs;
    $('campaign-status').textContent = `${done.state === 'cancelled' ? 'Cancelled' : 'Done'}: ${s.runs} of ${done.total} runs` +
      `; ours ${pct(s.ours.tasks_vs_oracle_mean)} of the oracle's tasks (baseline ${pct(s.baseline.tasks_vs_oracle_mean)})` +
      `; against the baseline ${s.vs_baseline.better} better, ${s.vs_baseline.equal} equal, ${s.vs_baseline.worse} worse` +
      `; ${s.clean ? 'clean' : 'NOT clean'}`;
    $('campaign-charts').replaceChildren(...summaryCharts(s));
    this.table(done.runs);
  }

  table(runs) {
    const head = document.createElement('tr');
    for (const h of ['run', 'tasks / oracle', 'ours ended', 'baseline', 'replans']) {
      head.append(Object.assign(document.createElement('th'), { textContent: h }));
    }
    const rows = runs.slice(0, MAX_ROWS).map((r) => {
      const tr = document.createElement('tr');
      tr.dataset.run = r.run;
      const cells = r.status !== 'ok'
        ? [r.run, r.status, r.detail, '', '']
        : [r.run, `${r.ours.tasks} / ${r.oracle.tasks}`, r.ours.outcome.replace('_', ' '),
           `${r.baseline.tasks}, ${r.baseline.outcome.replace('_', ' ')}`, r.ours.replans];
      for (const c of cells) tr.append(Object.assign(document.createElement('td'), { textContent: String(c) }));
      if (r.status === 'ok') tr.onclick = () => this.open(r.run);
      else tr.className = 'failed';
      return tr;
    });
    this.$('campaign-table').replaceChildren(head, ...rows);
    this.$('campaign-more').textContent = runs.length > MAX_ROWS ? `the first ${MAX_ROWS} of ${runs.length} runs` : '';
  }

  // Run `index` of the last campaign, simulated again by the server from its seed, in the replay view.
  async open(index) {
    try {
      const { events, run } = await api.campaignRun(index);
      for (const tr of this.$('campaign-table').querySelectorAll('tr')) tr.classList.toggle('open', tr.dataset.run === String(index));
      this.onOpenRun(index, events, run);
    } catch (e) {
      this.onError(e.message);
    }
  }
}
