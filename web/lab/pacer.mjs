// Pacing of a lab's simulation against the wall clock, apart from the DOM so that node
// can test it with a clock of its own: each animation frame steps in chunks until
// simulation time has caught up with the wall clock times the speed (1 = real time, 1/2
// ... 1/64 = slow motion) or kBudgetShare of the mean frame interval (10 ms at 60 Hz; at
// most kMaxBudgetMs when drawing itself is slow) is spent; time still owed then is
// dropped, so a slow machine shows a real-time factor below the speed rather than
// freezing. A wall-clock gap longer than kMaxGap between two frames (the page stalled) is
// skipped, and so is the gap after resync() (the lab calls it when its tab was hidden):
// slow frames of a busy machine (5 fps, some 400 ms apart) are still caught up. A chunk
// is about kChunkMs of stepping, from the measured cost of a step.
const kBudgetShare = 0.6;
const kMaxBudgetMs = 50;
const kChunkMs = 1;
const kMaxGap = 1;

// The slow-motion speeds, as simulate offers them (its '-' and '=' keys step through them).
export const kSpeeds = [1, 1 / 2, 1 / 4, 1 / 8, 1 / 16, 1 / 32, 1 / 64];

// The speed of kSpeeds after `speed`: slower (direction -1) or faster (+1), staying at
// the ends.
export function nextSpeed(speed, direction) {
  const i = kSpeeds.indexOf(speed);
  return kSpeeds[Math.min(kSpeeds.length - 1, Math.max(0, (i < 0 ? 0 : i) - direction))];
}

export class Pacer {
  // timestep: seconds per step; step(n): takes n steps; now(): the wall clock in ms.
  constructor({ timestep, step, now = () => performance.now() }) {
    this.timestep = timestep;
    this.stepSim = step;
    this.now = now;
    this.speed = 1;
    this.frameInterval = 1000 / 60;  // mean wall time between frames, ms
    this.msPerStep = 0.05;           // measured cost of one step, ms
    this.debt = 0;                   // simulated seconds owed to the clock
    this.lastFrame = null;           // the last frame's wall time, ms
    this.skipGap = false;            // the next frame's gap is skipped (see resync)
    // In total since made: wall seconds given up (budget spent, hidden tab), steps taken,
    // and ms spent stepping since the last takeBusy().
    this.dropped = 0;
    this.totalSteps = 0;
    this.busy = 0;
  }

  // One animation frame at wall time `frameTime` (ms): while `playing`, steps to keep up;
  // returns the number of steps taken.
  frame(frameTime, playing) {
    const wall = this.lastFrame === null ? 0 : (frameTime - this.lastFrame) / 1000;
    const gap = this.skipGap ? 0 : Math.min(kMaxGap, wall);
    this.skipGap = false;
    if (playing) this.dropped += wall - gap;
    if (gap > 0) this.frameInterval = 0.9 * this.frameInterval + 0.1 * 1000 * gap;
    this.lastFrame = frameTime;
    return playing ? this.advance(gap * this.speed) : 0;
  }

  // Steps `owed` more simulated seconds within the frame's budget; what is still owed
  // when the budget is spent is dropped. Returns the steps taken.
  advance(owedSeconds) {
    this.debt += owedSeconds;
    const start = this.now();
    const budget = Math.min(kMaxBudgetMs, kBudgetShare * this.frameInterval);
    let owed = Math.floor(this.debt / this.timestep + 1e-9);
    let spent = 0, taken = 0;
    while (owed > 0 && spent < budget) {
      const chunk = Math.min(owed, Math.max(1, Math.floor(kChunkMs / this.msPerStep)));
      this.stepSim(chunk);
      taken += chunk;
      const now = this.now();
      this.msPerStep = 0.8 * this.msPerStep + 0.2 * Math.max(1e-4, (now - start - spent) / chunk);
      spent = now - start;
      this.debt -= chunk * this.timestep;
      owed -= chunk;
    }
    if (owed > 0) {
      this.dropped += this.debt / this.speed;
      this.debt = 0;
    }
    this.totalSteps += taken;
    this.busy += spent;
    return taken;
  }

  // The wall time until the next frame is not to be caught up (the page was hidden).
  resync() {
    this.skipGap = true;
    this.clearDebt();
  }

  // Nothing owed (after a pause, a reset or a change of speed).
  clearDebt() {
    this.debt = 0;
  }

  // The ms spent stepping since the last call.
  takeBusy() {
    const busy = this.busy;
    this.busy = 0;
    return busy;
  }
}
