// report.html's 3D view: the vtk.js scene of shaftfem.outputs.web_scene, one mode shown
// at a time, stepped through and animated with vtk.js's own objects. The viewer keeps
// its render window in window.global.renderWindow; the scene's actors are the modes at
// their largest drawn displacement, then the surface at rest (hidden: the base the
// motion is measured from), then the grey shaft, the bearings and the parts.
(function () {
  "use strict";
  const view3d = JSON.parse(document.getElementById("shaftfem-modes").textContent);
  const modes = view3d.modes;
  const n = modes.length;
  const view = document.getElementById("view3d");
  const label = document.getElementById("mode-label");
  const select = document.getElementById("mode-select");
  const play = document.getElementById("mode-play");
  const moves = [];
  let actors = null;
  let scene = null;
  let base = null;
  let current = 0;
  let playing = false;
  let t0 = 0;

  function points(actor) {
    return actor.getMapper().getInputData().getPoints().getData();
  }

  function render() {
    window.global.renderWindow.render();
  }

  function start() {
    const rw = window.global && window.global.renderWindow;
    // pyvista's window has more than one renderer: the shaft is in the one with actors
    const renderer = rw ? rw.getRenderers()
      .reduce((a, b) => (b.getActors().length > a.getActors().length ? b : a)) : null;
    const found = renderer ? renderer.getActors() : [];
    if (found.length < n + 2 || !found[n].getMapper() || !found[n].getMapper().getInputData()) {
      setTimeout(start, 50);
      return;
    }
    actors = found;
    scene = renderer;
    base = Float32Array.from(points(actors[n]));
    actors[n].setVisibility(false);
    for (let k = 0; k < n; k++) {
      const p = points(actors[k]);
      const d = new Float32Array(p.length);
      for (let i = 0; i < p.length; i++) d[i] = p[i] - base[i];
      moves.push(d);
    }
    const asked = /mode=(\d+)/.exec(window.location.hash);
    show(asked ? parseInt(asked[1], 10) - 1 : 0);
    view.dataset.ready = "true";
  }

  function place(phase) {
    const data = actors[current].getMapper().getInputData();
    const p = data.getPoints().getData();
    const d = moves[current];
    for (let i = 0; i < p.length; i++) p[i] = base[i] + phase * d[i];
    data.getPoints().modified();
    data.modified();
  }

  function look(k) {
    // seen square from the side, across the mode's plane of motion, filling the view
    // (as in modes.png); the reader turns it from there
    const v = view3d.views[k];
    const camera = scene.getActiveCamera();
    camera.setParallelProjection(true);
    camera.setFocalPoint(...v.focus);
    camera.setPosition(...v.position);
    camera.setViewUp(...v.up);
    camera.setParallelScale(v.parallelScale * Math.max(
      1, (view3d.width / view3d.height) / (view.clientWidth / view.clientHeight)));
    scene.resetCameraClippingRange();
  }

  function show(k) {
    if (actors === null) return;
    current = ((k % n) + n) % n;
    look(current);
    for (let i = 0; i < n; i++) actors[i].setVisibility(i === current);
    place(1);
    label.textContent = modes[current];
    select.value = String(current);
    view.dataset.mode = String(current + 1);
    render();
  }

  function frame(t) {
    if (!playing) return;
    place(Math.sin((2 * Math.PI * (t - t0)) / 1500));
    render();
    window.requestAnimationFrame(frame);
  }

  function toggle() {
    playing = !playing;
    play.textContent = playing ? "stop" : "animate";
    if (playing) {
      t0 = performance.now();
      window.requestAnimationFrame(frame);
    } else {
      place(1);
      render();
    }
  }

  modes.forEach(function (text, k) {
    const option = document.createElement("option");
    option.value = String(k);
    option.textContent = text;
    select.appendChild(option);
  });
  select.addEventListener("change", function () { show(parseInt(select.value, 10)); });
  document.getElementById("mode-previous").addEventListener("click", function () { show(current - 1); });
  document.getElementById("mode-next").addEventListener("click", function () { show(current + 1); });
  play.addEventListener("click", toggle);
  window.addEventListener("hashchange", function () {
    const asked = /mode=(\d+)/.exec(window.location.hash);
    if (asked) show(parseInt(asked[1], 10) - 1);
  });
  window.loadDataSet = function () {
    window.OfflineLocalView.load(view, { base64Str: view.dataset.scene });
    delete view.dataset.scene;
    start();
  };
})();
