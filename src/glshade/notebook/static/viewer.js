// glshade's notebook viewer: the kernel renders (headless, glshade's own renderer) and sends
// PNG frames; this draws them on a canvas, pixel for pixel, and sends the gestures back:
// drag (arcball, right or shift: pan), wheel (dolly), keys (1-6 modes, v views, o, r, t
// path tracing, ...),
// click (pick, when picking is on). Moves are sent one per frame received (flow control).
function render({ model, el }) {
  const root = document.createElement("div");
  root.className = "glshade-viewer";
  const bar = document.createElement("div");
  bar.className = "glshade-bar";
  const modes = ["flat", "gouraud", "phong", "normals", "depth"];
  const buttons = {};
  for (const m of modes) {
    const b = document.createElement("button");
    b.textContent = m;
    b.dataset.mode = m;
    b.addEventListener("click", () => model.send({ event: "mode", mode: m }));
    buttons[m] = b;
    bar.appendChild(b);
  }
  const split = document.createElement("select");
  split.className = "glshade-compare";
  for (const m of ["", ...modes]) {
    const o = document.createElement("option");
    o.value = m;
    o.textContent = m ? `split: ${m}` : "no split";
    split.appendChild(o);
  }
  split.addEventListener("change", () => model.send({ event: "compare", mode: split.value }));
  bar.appendChild(split);
  const reset = document.createElement("button");
  reset.textContent = "reset";
  reset.addEventListener("click", () => model.send({ event: "key", key: "r" }));
  bar.appendChild(reset);
  const trace = document.createElement("button");  // path tracing on and off (key t)
  trace.textContent = "trace";
  trace.className = "glshade-trace";
  trace.addEventListener("click", () => model.send({ event: "key", key: "t" }));
  bar.appendChild(trace);

  const stage = document.createElement("div");
  stage.className = "glshade-stage";
  const canvas = document.createElement("canvas");
  canvas.tabIndex = 0;
  const divider = document.createElement("div");
  divider.className = "glshade-divider";
  stage.append(canvas, divider);
  const status = document.createElement("div");
  status.className = "glshade-status";
  root.append(bar, stage, status);
  el.appendChild(root);

  let waiting = false;   // a gesture sent, its frame not yet drawn
  let queued = null;     // the latest move while waiting
  function send(msg) {
    if (msg.event === "move" && waiting) { queued = msg; return; }
    waiting = msg.event !== "up";
    model.send(msg);
  }
  function point(e) {
    const r = canvas.getBoundingClientRect();
    return { x: (e.clientX - r.left) * canvas.width / r.width,
             y: (e.clientY - r.top) * canvas.height / r.height };
  }
  canvas.addEventListener("contextmenu", (e) => e.preventDefault());
  canvas.addEventListener("pointerdown", (e) => {
    canvas.focus();
    canvas.setPointerCapture(e.pointerId);
    const p = point(e);
    send({ event: "down", x: p.x, y: p.y, button: e.button === 2 ? "right" : "left",
           shift: e.shiftKey });
  });
  canvas.addEventListener("pointermove", (e) => {
    if (e.buttons === 0) return;
    const p = point(e);
    send({ event: "move", x: p.x, y: p.y });
  });
  canvas.addEventListener("pointerup", (e) => {
    if (queued) { model.send(queued); queued = null; }
    model.send({ event: "up" });
  });
  canvas.addEventListener("wheel", (e) => {
    e.preventDefault();
    send({ event: "wheel", dy: e.deltaY < 0 ? 1 : -1 });
  }, { passive: false });
  canvas.addEventListener("keydown", (e) => {
    if (e.key.length === 1) { e.preventDefault(); send({ event: "key", key: e.key }); }
  });

  async function draw() {
    const revision = model.get("revision"), view = model.get("view");
    const data = model.get("png");
    const w = model.get("width"), h = model.get("height");
    if (canvas.width !== w || canvas.height !== h) {
      canvas.width = w; canvas.height = h;
      canvas.style.width = `${w}px`; canvas.style.height = `${h}px`;
    }
    if (data && data.byteLength) {
      const bitmap = await createImageBitmap(new Blob([data], { type: "image/png" }),
                                             { premultiplyAlpha: "none",
                                               colorSpaceConversion: "none" });
      canvas.getContext("2d").drawImage(bitmap, 0, 0);
      bitmap.close();
    }
    const mode = model.get("mode"), other = model.get("split");
    for (const m of modes) buttons[m].classList.toggle("active", m === mode);
    split.value = other;
    divider.style.display = other ? "block" : "none";
    divider.style.left = `${Math.floor(w / 2)}px`;
    status.textContent = model.get("status");
    canvas.dataset.revision = String(revision);
    root.dataset.view = JSON.stringify(view);
    waiting = false;
    if (queued) { const q = queued; queued = null; send(q); }
  }
  // frames drawn one after another, in order (each decode is asynchronous; a later frame's
  // must not be overdrawn by an earlier one's)
  let drawing = Promise.resolve();
  const next = () => { drawing = drawing.then(draw, draw); };
  model.on("change:revision", next);
  next();
}
export default { render };
