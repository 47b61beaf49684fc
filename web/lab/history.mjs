// Scrubbing the last seconds of a simulation, as simulate's history slider: the engine
// records every step's state (sim.history() says how many are kept and how far back the
// state shown is; sim.scrub(back) loads the state `back` steps before the newest). Apart
// from the DOM so that node can test it with a stand-in for the engine.
export class HistoryScrubber {
  // sim: {history(): {size, back, newest}, scrub(back)}.
  constructor(sim) {
    this.sim = sim;
  }

  // How many steps before the newest state the state shown is (0: the newest).
  back() {
    return this.sim.history().back;
  }

  // Loads the state `back` steps before the newest, clamped to the states kept; false
  // when there is nothing to move to (no history, or already there).
  scrubTo(back) {
    const { size, back: now } = this.sim.history();
    const target = Math.max(0, Math.min(size - 1, Math.round(back)));
    if (size === 0 || target === now) return false;
    this.sim.scrub(target);
    return true;
  }

  // What the slider shows at simulation time `time`: {slider: {max, value}} as strings
  // (the oldest state at 0, the newest at max) and the text beside it, the seconds
  // before the newest state ("-0.250 s"; "0.000 s" at the newest).
  sliderState(time) {
    const { size, back, newest } = this.sim.history();
    const max = Math.max(0, size - 1);
    const seconds = back > 0 ? time - newest : 0;
    return { slider: { max: String(max), value: String(max - back) },
             text: `${seconds < 0 ? '-' : ''}${Math.abs(seconds).toFixed(3)} s` };
  }
}
