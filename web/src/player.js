// SPDX-License-Identifier: MIT
// The event player: plays a simulation's events (live from the server's stream, or an uploaded
// `simulate --log` file) in the order they happened, paced by their simulated times (`t_s`) at
// `speed` simulated seconds per second, and moves the robot smoothly along each action between
// its start and its end. The simulated robot runs much faster than real time, so the stream
// arrives ahead of the player, which queues it.
import { pointOnPipe } from './geometry.js';

// Where the action of an `action` event takes the robot (its step in the paper's text and its
// parameters as fusion prints them), or null when it does not say.
export function actionTarget(map, event, mission) {
  const words = event.step.split(/\s+/);
  const pipe = map.pipeByName.get(words[1]);
  if (event.kind === 'drive_to_manhole' || event.kind === 'pass_manhole') {
    const manhole = map.manholeByName.get(words[event.kind === 'pass_manhole' ? 1 : 2]);
    return manhole?.position ?? null;
  }
  if (!pipe) return null;
  const at = /at (\d+(?:\.\d+)?) m/.exec(event.parameters ?? '');
  if (at) return pointOnPipe(pipe, Number(at[1]));
  const end = /end \d -> (\d)/.exec(event.parameters ?? '');
  if (end) return end[1] === '0' ? pipe.from : pipe.to;
  const task = mission?.tasks.find((t) => t.at?.pipe === pipe.name && t.at.offset_m !== undefined);
  return pointOnPipe(pipe, task?.at.offset_m);
}

// "in pipe P1 at 2.95 m", "in manhole M3": a point, or null.
export function wherePoint(map, where) {
  const inPipe = /pipe (\S+) at (\d+(?:\.\d+)?) m/.exec(where ?? '');
  if (inPipe && map.pipeByName.has(inPipe[1])) return pointOnPipe(map.pipeByName.get(inPipe[1]), Number(inPipe[2]));
  const inManhole = /manhole (\S+)/.exec(where ?? '');
  return inManhole ? map.manholeByName.get(inManhole[1])?.position ?? null : null;
}

// onEvent(type, data, meta) for each event when its time comes; onRobot(point) every frame.
export class Player {
  constructor({ onEvent, onRobot, now = () => performance.now() }) {
    Object.assign(this, { onEvent, onRobot, now });
    this.speed = 20;
    this.reset();
  }

  reset(start = null) {
    cancelAnimationFrame(this.frame);
    this.queue = [];
    this.simTime = 0;
    this.last = null;
    this.motion = start ? { from: start, to: start, t0: 0, t1: 0 } : null;
    this.frame = null;
  }

  // An event with its arrival time (the page's clock) and the server's stamp, if any.
  push(type, data, meta = {}) {
    this.queue.push({ type, data, meta });
    if (this.frame === null) this.frame = requestAnimationFrame(() => this.tick());
  }

  get idle() { return this.queue.length === 0; }

  // Points of the robot now: where the current motion has got to.
  robotAt(t) {
    const m = this.motion;
    if (!m) return null;
    const f = m.t1 > m.t0 ? Math.max(0, Math.min(1, (t - m.t0) / (m.t1 - m.t0))) : 1;
    return [m.from[0] + f * (m.to[0] - m.from[0]), m.from[1] + f * (m.to[1] - m.from[1])];
  }

  // Starts a motion to `to` from where the robot is, over [t0, t0 + duration].
  moveTo(to, t0, duration) {
    const from = this.robotAt(t0) ?? to;
    this.motion = { from, to, t0, t1: t0 + duration };
  }

  placeAt(point, t) { this.motion = { from: point, to: point, t0: t, t1: t }; }

  tick() {
    const wall = this.now();
    // Infinite speed: everything queued at once; else simulated time advances with the wall.
    if (this.last !== null) this.simTime += ((wall - this.last) / 1000) * this.speed;
    this.last = wall;
    while (this.queue.length > 0) {
      const next = this.queue[0];
      const t = next.data.t_s;
      if (t !== undefined && t > this.simTime && Number.isFinite(this.speed)) break;
      this.queue.shift();
      if (t !== undefined) this.simTime = Math.max(this.simTime, t);
      this.onEvent(next.type, next.data, next.meta);
    }
    const end = this.motion ? this.motion.t1 : 0;
    this.onRobot(this.robotAt(Number.isFinite(this.speed) ? this.simTime : Math.max(this.simTime, end)));
    const moving = this.motion && this.simTime < this.motion.t1 && Number.isFinite(this.speed);
    this.frame = this.queue.length > 0 || moving ? requestAnimationFrame(() => this.tick()) : null;
    if (this.frame === null) this.last = null;
  }
}
