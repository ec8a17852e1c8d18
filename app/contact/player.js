// The browser's animation player (app/contact/player.py): the body of a Bokeh CustomJS
// whose args are the frames, the sources and texts it writes; see player.py's docstring.
// (`shown`: the tau of the frame on screen while playing, which Play / Pause reports)
// (`watching`: the IntersectionObserver of the page's plots while playing)
const st = window.__zharii_player || (window.__zharii_player =
  {raf: null, held: null, writing: false, watched: new Set(), shown: null, watching: null});
if (st.raf !== null) { cancelAnimationFrame(st.raf); st.raf = null; }
const get = (src) => (src.data instanceof Map ? Object.fromEntries(src.data) : src.data);
// what this script changes while it plays: [model, property] (controls found on the
// page by the server, absent in a document without them; the sources it copies frames
// into, in place)
const texts = [[caption, "text"], [phase_label, "text"], [phase_label, "text_color"]];
for (const [m, a] of [[entry, "value"], [slider, "value"], [formula, "text"]]) {
  if (m) { texts.push([m, a]); }
}
for (const src of [traction, disc, ...markers, ...sprites.map((s) => s[0])]) {
  texts.push([src, "data"]);
}
const key = (m, a) => m.id + ":" + a;
// a copy of what the server holds (a source's columns are copied: frames are written
// into them in place)
const copy = (v) => v instanceof Map ? new Map([...v].map(([k, c]) => [k, c.slice()])) :
  (v !== null && typeof v === "object" && !Array.isArray(v)) ?
    Object.fromEntries(Object.entries(v).map(([k, c]) => [k, c.slice()])) : v;
const held = (m, a) => [m, a, copy(m[a])];
function put(m, a, v) {                        // shown here, not sent to the server
  st.writing = true;
  try { m.setv({[a]: v}, {sync: false}); } finally { st.writing = false; }
}
const count = () => { const t = get(frames).tau; return t ? t.length : 0; };
// while playing, a plot out of the viewport (or in a closed tab) is not painted
// (BokehJS's `hold_render`); it is painted, with the frame of that moment, when it
// comes into view, and every plot is painted again when the player stops
function watch() {
  if (st.watching !== null) { return; }
  const plots = new Map();
  for (const v of Bokeh.index.query((v) => v.model.type === "Figure"
                                     && v.model.document === frames.document)) {
    plots.set(v.el, v.model);
  }
  const observer = new IntersectionObserver((entries) => {
    if (st.watching === null || st.watching.observer !== observer) { return; }
    for (const e of entries) {
      const plot = plots.get(e.target);
      if (plot.hold_render === e.isIntersecting) {
        plot.setv({hold_render: !e.isIntersecting}, {sync: false});
      }
    }
  });
  for (const el of plots.keys()) { observer.observe(el); }
  st.watching = {observer, plots: [...plots.values()]};
}
function unwatch() {
  if (st.watching === null) { return; }
  st.watching.observer.disconnect();
  for (const plot of st.watching.plots) {
    if (plot.hold_render) { plot.setv({hold_render: false}, {sync: false}); }
  }
  st.watching = null;
}
function stop() {                              // show what the server holds
  st.shown = null;
  if (st.raf !== null) { cancelAnimationFrame(st.raf); st.raf = null; }
  unwatch();
  if (st.held !== null) {
    for (const [m, a, v] of st.held.values()) { put(m, a, v); }
    st.held = null;
  }
}
// stopped at once when the frames are emptied, before the rest of the server's message
// is applied (this script runs after it): a value that message sets to the one on
// screen changes nothing in BokehJS, and is then shown, not the one held before it
if (!st.watched.has(frames.id)) {
  st.watched.add(frames.id);
  frames.properties.data.change.connect(() => { if (count() === 0) { stop(); } });
}
const F = get(frames);
const K = count();
if (K === 0) {
  stop();
  return;
}
if (st.held === null) { st.held = new Map(); }
watch();
for (const [m, a] of texts) {                  // what the server holds, kept up to date
  const k = key(m, a);
  if (!st.held.has(k)) { st.held.set(k, held(m, a)); }
  if (!st.watched.has(k)) {
    st.watched.add(k);
    m.properties[a].change.connect(() => {
      if (st.held !== null && !st.writing) { st.held.set(k, held(m, a)); }
    });
  }
}
const P = get(profiles);
const L = P.r.length / K;
const names = Object.keys(P);  // the profile's columns (traction.PROFILE_COLUMNS)
const seconds = F.seconds[0], speed = F.speed[0], start = F.start[0];
const t0 = performance.now();
let last = -1, phase = -1;
function draw(k) {
  const T = get(traction);
  for (const n of names) { const dst = T[n], src = P[n];
    for (let i = 0; i < L; i++) { dst[i] = src[k * L + i]; } }
  traction.change.emit();
  const D = get(disc);
  D.inner[1] = F.b[k]; D.outer[0] = F.b[k]; D.outer[1] = F.a[k];
  D.color[1] = F.disc_color[k]; D.label[1] = F.disc_label[k];
  disc.change.emit();
  for (const [dst, src, cols] of sprites) {    // scenes drawn from a few rows each
    const S = get(src), D = get(dst), n = S[cols[0]].length / K;
    for (const c of cols) { const d = D[c], s = S[c];
      for (let i = 0; i < n; i++) { d[i] = s[k * n + i]; } }
    dst.change.emit();
  }
  for (let j = 0; j < markers.length; j++) {
    const M = get(markers[j]), cols = marker_columns[j];
    for (let i = 0; i < cols.length; i++) { M.x[i] = F.tau[k]; M.y[i] = F[cols[i]][k]; }
    markers[j].change.emit();
  }
  st.shown = F.tau[k];
  put(caption, "text", F.caption[k]);
  if (entry) { put(entry, "value", F.tau_text[k]); }
  if (slider) { put(slider, "value", F.tau[k]); }
  if (F.phase[k] !== phase) {                  // a few times per contact
    phase = F.phase[k];
    put(phase_label, "text", F.phase_name[k]);
    put(phase_label, "text_color", F.phase_color[k]);
    if (formula) { put(formula, "text", formulas[phase]); }
  }
}
function tick(now) {
  // a frame's timestamp may precede t0 by a little: keep progress in [0, 1)
  const p = (start + speed * Math.max(0, now - t0) / 1000 / seconds) % 1;
  const k = Math.max(0, Math.min(K - 1, Math.floor(p * K)));
  if (k !== last) { draw(k); last = k; }
  st.raf = requestAnimationFrame(tick);
}
last = Math.max(0, Math.min(K - 1, Math.floor(start * K)));
draw(last);                                    // at once, with this message
st.raf = requestAnimationFrame(tick);
