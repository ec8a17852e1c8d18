// Play / Pause, Step and Speed of the lesson file (app/contact/lesson.py), over the
// explorer's own player (app/contact/player.js): the body of a Bokeh CustomJS whose args
// are `frames` (the player's frame store), the buttons `play` and `step`, the `speed`
// menu, `action` ("play", "step" or "speed") and `first` (the frame shown at load).
// Each press gives the player the frames again with a new start and speed: playing, at
// the chosen speed from the frame on screen; paused or stepped, at speed 0 on a frame.
const lesson = window.__zharii_lesson ||
  (window.__zharii_lesson = {store: frames.data, playing: false});
const get = (d, k) => (d instanceof Map ? d.get(k) : d[k]);
const taus = get(lesson.store, "tau");
const K = taus.length;
const shown = (window.__zharii_player || {}).shown;
let k = shown == null ? first : taus.indexOf(shown);
if (k < 0) { k = first; }
if (action === "play") { lesson.playing = !lesson.playing; }
if (action === "step") { lesson.playing = false; k = (k + 1) % K; }
function give(frame, rate) {          // the store, with the start and speed of this press
  const start = new Array(K).fill((frame + 0.5) / K), speeds = new Array(K).fill(rate);
  let data;
  if (lesson.store instanceof Map) {
    data = new Map(lesson.store);
    data.set("start", start); data.set("speed", speeds);
  } else {
    data = Object.assign({}, lesson.store, {start: start, speed: speeds});
  }
  frames.data = data;
}
give(k, lesson.playing ? parseFloat(speed.value) : 0);
play.label = lesson.playing ? "❚❚ Pause" : "▶ Play";
