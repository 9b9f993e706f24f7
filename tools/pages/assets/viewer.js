'use strict';
// clothref's trace viewer (docs/pictures.md): plays the frames `clothref view` embedded in the page.
// No library and no network. A Canvas 2-D renderer that sorts triangles back to front is enough for
// a 25x25 cloth and needs no GPU, so the page draws the same picture on any machine, headless too.
// Every text that comes from a trace or a user is set with textContent, never parsed as HTML.

var clothrefViewers = [];  // one handle per mounted viewer, for the browser tests

// options: {layout: 'overlay' | 'side' (two traces; default overlay), stills: N (a row of N small
// pictures at evenly spread times above the player, both traces side by side in each)}
function mountViewer(root, data, options) {
  options = options || {};
  const started = performance.now();
  const two = data.traces.length === 2;

  // ---- data -------------------------------------------------------------------------------
  function decode(text, Type) {
    const bytes = atob(text);
    const buffer = new Uint8Array(bytes.length);
    for (let i = 0; i < bytes.length; ++i) buffer[i] = bytes.charCodeAt(i);
    return new Type(buffer.buffer);
  }
  const frames = data.frame_steps.length;
  const frameT = decode(data.frame_t, Float64Array);
  const positions = data.positions.map((text) => decode(text, Float32Array));
  let floatsPerFrame = 0;
  let cloth = null;    // {offset, count}
  let spheres = null;  // {offset, count}
  for (const body of data.bodies) {
    if (body.name === 'cloth') cloth = {offset: floatsPerFrame, count: body.particles};
    if (body.name === 'spheres') spheres = {offset: floatsPerFrame, count: body.particles};
    floatsPerFrame += 3 * body.particles;
  }
  const distance = two && data.distance ? decode(data.distance, Float32Array) : null;
  let distanceMax = 0;
  if (distance)
    for (const d of distance)
      if (isFinite(d) && d > distanceMax) distanceMax = d;
  const differenceSteps = two ? data.difference.steps : [];
  const differenceLargest = two ? decode(data.difference.largest, Float32Array) : null;
  const firstStep = two && data.first_difference ? data.first_difference.step : null;
  const firstFrame = firstStep === null ? -1 : data.frame_steps.indexOf(firstStep);

  // faces (grid cloth) or edges (cloth given particle by particle)
  const triangles = [];
  const edges = [];
  if (cloth && data.cloth_mesh && data.cloth_mesh.grid) {
    const n = data.cloth_mesh.grid;
    for (let i = 0; i + 1 < n; ++i)
      for (let j = 0; j + 1 < n; ++j) {
        const a = i * n + j, b = a + 1, c = a + n, d = c + 1;
        triangles.push([a, b, d], [a, d, c]);
        edges.push([a, b], [a, c]);
        if (i + 2 === n) edges.push([c, d]);
        if (j + 2 === n) edges.push([b, d]);
      }
  } else if (cloth && data.cloth_mesh && data.cloth_mesh.springs) {
    const s = data.cloth_mesh.springs;
    for (let k = 0; k + 1 < s.length; k += 2) edges.push([s[k], s[k + 1]]);
  }
  const fixed = new Set(data.fixed || []);

  // ---- page elements ----------------------------------------------------------------------
  function element(tag, className, text) {
    const e = document.createElement(tag);
    if (className) e.className = className;
    if (text !== undefined) e.textContent = text;
    return e;
  }
  root.classList.add('cv-root');
  root.tabIndex = 0;
  for (const t of data.traces) {
    const info = element('p', 'cv-info');
    const dt = Number(t.dt).toPrecision(3);
    info.textContent = `${t.label}: ${t.scene || 'scene'}, ${t.integrator}, ${t.precision}, ` +
                       `dt ${dt} s, ${t.steps} steps, stride ${t.stride}`;
    root.appendChild(info);
  }
  const canvas = element('canvas', 'cv-canvas');
  root.appendChild(canvas);
  const controls = element('div', 'cv-controls');
  const playButton = element('button', 'cv-play', '\u25B6');
  playButton.title = 'Play / pause (space)';
  const backButton = element('button', 'cv-back', '\u25C0|');
  backButton.title = 'Previous frame (left arrow)';
  const nextButton = element('button', 'cv-next', '|\u25B6');
  nextButton.title = 'Next frame (right arrow)';
  const sliderBox = element('div', 'cv-slider-box');
  const slider = element('input', 'cv-slider');
  slider.type = 'range';
  slider.min = 0;
  slider.max = Math.max(0, frames - 1);
  slider.value = 0;
  sliderBox.appendChild(slider);
  if (firstFrame >= 0) {
    const marker = element('div', 'cv-marker');
    marker.style.left = (frames > 1 ? (100 * firstFrame) / (frames - 1) : 0) + '%';
    marker.dataset.step = String(firstStep);
    marker.title = `first difference: step ${firstStep}`;
    sliderBox.appendChild(marker);
  }
  const timeLabel = element('span', 'cv-time');
  controls.append(playButton, backButton, nextButton, sliderBox, timeLabel);
  let layout = two && options.layout === 'side' ? 'side' : 'overlay';
  if (two) {
    const select = element('select', 'cv-layout');
    for (const [value, text] of [['overlay', 'overlaid'], ['side', 'side by side']]) {
      const option = element('option', null, text);
      option.value = value;
      select.appendChild(option);
    }
    select.value = layout;
    select.addEventListener('change', () => {
      layout = select.value;
      draw();
    });
    controls.appendChild(select);
    const legend = element('span', 'cv-legend');
    legend.append(element('span', null, '0'), element('span', 'cv-legend-bar'),
                  element('span', null, `${distanceMax.toPrecision(3)} m from the other trace`));
    controls.appendChild(legend);
  }
  root.appendChild(controls);
  const shown = frames < data.recorded
                    ? `Showing ${frames} of ${data.recorded} recorded steps, evenly spread ` +
                      `(about one in ${Math.round((data.recorded - 1) / Math.max(1, frames - 1))})` +
                      (two ? '; the first differing step is always shown.' : '.')
                    : `Showing all ${frames} recorded steps.`;
  root.appendChild(element('p', 'cv-note cv-decimation', shown));
  let plot = null;
  if (two) {
    const first = element('p', 'cv-first ' + (firstStep === null ? 'cv-same' : 'cv-differ'));
    first.textContent = firstStep === null
        ? 'The two traces are identical at every common recorded step.'
        : `First difference at step ${firstStep}` +
          (data.first_difference.t === null ? '' : ` (t = ${data.first_difference.t.toPrecision(6)} s)`) +
          `; largest position difference ${data.largest_difference === null ? 'infinite'
                                            : data.largest_difference.toPrecision(3) + ' m'}.`;
    first.dataset.step = firstStep === null ? '' : String(firstStep);
    root.appendChild(first);
    plot = element('canvas', 'cv-plot');
    root.appendChild(plot);
  }

  // ---- camera -----------------------------------------------------------------------------
  const camera = {yaw: 0.7, pitch: 0.45, distance: 1, target: [0, 0, 0]};
  function resetCamera() {
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    const grow = (x, y, z, r) => {
      const p = [x, y, z];
      for (let k = 0; k < 3; ++k) {
        if (!isFinite(p[k])) return;
        lo[k] = Math.min(lo[k], p[k] - r);
        hi[k] = Math.max(hi[k], p[k] + r);
      }
    };
    // the first frame frames the scene: a run that blows up later must not shrink it to a dot
    const p = positions[0];
    if (cloth)
      for (let i = 0; i < cloth.count; ++i) {
        const o = cloth.offset + 3 * i;
        grow(p[o], p[o + 1], p[o + 2], 0);
      }
    if (spheres)
      for (let i = 0; i < spheres.count; ++i) {
        const o = spheres.offset + 3 * i;
        grow(p[o], p[o + 1], p[o + 2], data.sphere_radii[i] || 0);
      }
    if (!(lo[0] <= hi[0])) {
      lo.fill(-1);
      hi.fill(1);
    }
    camera.target = [0, 1, 2].map((k) => (lo[k] + hi[k]) / 2);
    const size = Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-3);
    camera.distance = 1.5 * size;
    camera.yaw = 0.7;
    camera.pitch = 0.45;
  }
  resetCamera();

  function basis() {
    const cp = Math.cos(camera.pitch), sp = Math.sin(camera.pitch);
    const back = [cp * Math.sin(camera.yaw), sp, cp * Math.cos(camera.yaw)];
    const eye = camera.target.map((t, k) => t + camera.distance * back[k]);
    const forward = back.map((v) => -v);
    let right = [forward[1] * 0 - forward[2] * 1, forward[2] * 0 - forward[0] * 0,
                 forward[0] * 1 - forward[1] * 0];  // forward x (0, 1, 0)
    const length = Math.hypot(right[0], right[1], right[2]) || 1;
    right = right.map((v) => v / length);
    const up = [right[1] * forward[2] - right[2] * forward[1],
                right[2] * forward[0] - right[0] * forward[2],
                right[0] * forward[1] - right[1] * forward[0]];
    return {eye, forward, right, up};
  }

  // ---- drawing ----------------------------------------------------------------------------
  const viridis = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];
  function colourOf(d) {
    if (!isFinite(d)) return [230, 0, 200];
    const x = distanceMax > 0 ? Math.min(1, Math.max(0, d / distanceMax)) * 4 : 0;
    const i = Math.min(3, Math.floor(x)), f = x - i;
    return [0, 1, 2].map((k) => viridis[i][k] * (1 - f) + viridis[i + 1][k] * f);
  }
  const traceColours = [[70, 120, 180], [230, 140, 50]];

  // The camera's projection into the viewport (x0, y0, w, h): project(values, offset) gives the
  // screen x, y and depth of the point at values[offset..offset+2], or null behind the camera.
  function projector(x0, y0, w, h) {
    const {eye, forward, right, up} = basis();
    const focal = (0.5 * h) / Math.tan(0.4);
    const cx = x0 + w / 2, cy = y0 + h / 2;
    const project = (p, o) => {
      const d = [p[o] - eye[0], p[o + 1] - eye[1], p[o + 2] - eye[2]];
      const z = d[0] * forward[0] + d[1] * forward[1] + d[2] * forward[2];
      if (!(z > 1e-6)) return null;
      const x = d[0] * right[0] + d[1] * right[1] + d[2] * right[2];
      const y = d[0] * up[0] + d[1] * up[1] + d[2] * up[2];
      const s = [cx + (focal * x) / z, cy - (focal * y) / z, z];
      return isFinite(s[0]) && isFinite(s[1]) ? s : null;
    };
    return {project, focal, forward, up};
  }

  function drawScene(ctx, x0, y0, w, h, frame, trace, overlay) {
    const {project, focal, forward, up} = projector(x0, y0, w, h);
    const light = [0, 1, 2].map((k) => 0.8 * -forward[k] + 0.6 * up[k]);
    const items = [];
    const base = frame * floatsPerFrame;
    const p = positions[trace];
    const colourByDistance = distance && distanceMax > 0 && !overlay.wire;
    if (cloth && triangles.length > 0) {
      const screen = new Array(cloth.count);
      for (let i = 0; i < cloth.count; ++i) screen[i] = project(p, base + cloth.offset + 3 * i);
      for (const [a, b, c] of triangles) {
        const sa = screen[a], sb = screen[b], sc = screen[c];
        if (!sa || !sb || !sc) continue;
        const oa = base + cloth.offset + 3 * a, ob = base + cloth.offset + 3 * b,
              oc = base + cloth.offset + 3 * c;
        const u = [p[ob] - p[oa], p[ob + 1] - p[oa + 1], p[ob + 2] - p[oa + 2]];
        const v = [p[oc] - p[oa], p[oc + 1] - p[oa + 1], p[oc + 2] - p[oa + 2]];
        const n = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
        const nl = Math.hypot(n[0], n[1], n[2]) || 1;
        const ll = Math.hypot(light[0], light[1], light[2]);
        const shade = 0.35 + 0.65 * Math.abs((n[0] * light[0] + n[1] * light[1] + n[2] * light[2]) /
                                             (nl * ll));
        let colour = traceColours[trace];
        if (colourByDistance) {
          const o = frame * cloth.count;
          // the largest of its corners: a single particle that left shows as a spot
          colour = colourOf(Math.max(distance[o + a], distance[o + b], distance[o + c]));
        }
        items.push({z: (sa[2] + sb[2] + sc[2]) / 3, kind: 0, pts: [sa, sb, sc], colour, shade});
      }
    }
    if (spheres)
      for (let i = 0; i < spheres.count; ++i) {
        const s = project(p, base + spheres.offset + 3 * i);
        const r = data.sphere_radii[i] || 0;
        if (s && r > 0) items.push({z: s[2], kind: 1, pts: [s], radius: (focal * r) / s[2]});
      }
    items.sort((m, n) => n.z - m.z);  // far first
    ctx.lineJoin = 'round';
    for (const item of items) {
      if (item.kind === 0) {
        const [r, g, b] = item.colour.map((c) => Math.round(c * item.shade));
        ctx.fillStyle = ctx.strokeStyle = `rgb(${r},${g},${b})`;
        ctx.lineWidth = 0.6;  // hides the seams between triangles
        ctx.beginPath();
        ctx.moveTo(item.pts[0][0], item.pts[0][1]);
        ctx.lineTo(item.pts[1][0], item.pts[1][1]);
        ctx.lineTo(item.pts[2][0], item.pts[2][1]);
        ctx.closePath();
        ctx.fill();
        ctx.stroke();
      } else {
        const [sx, sy] = item.pts[0];
        const gradient = ctx.createRadialGradient(sx - item.radius * 0.35, sy - item.radius * 0.35,
                                                  item.radius * 0.1, sx, sy, item.radius);
        gradient.addColorStop(0, trace === 0 ? '#f3c0c0' : '#f6dcb8');
        gradient.addColorStop(1, trace === 0 ? '#a23b3b' : '#a86a1e');
        ctx.fillStyle = gradient;
        ctx.beginPath();
        ctx.arc(sx, sy, item.radius, 0, 2 * Math.PI);
        ctx.fill();
      }
    }
    // cloth given particle by particle: its springs and particles
    if (cloth && triangles.length === 0) {
      ctx.strokeStyle = `rgb(${traceColours[trace].join(',')})`;
      ctx.lineWidth = 1.5;
      for (const [a, b] of edges) {
        const sa = project(p, base + cloth.offset + 3 * a), sb = project(p, base + cloth.offset + 3 * b);
        if (!sa || !sb) continue;
        ctx.beginPath();
        ctx.moveTo(sa[0], sa[1]);
        ctx.lineTo(sb[0], sb[1]);
        ctx.stroke();
      }
      for (let i = 0; i < cloth.count; ++i) {
        const s = project(p, base + cloth.offset + 3 * i);
        if (!s) continue;
        ctx.fillStyle = fixed.has(i) ? '#333' : `rgb(${traceColours[trace].join(',')})`;
        ctx.beginPath();
        ctx.arc(s[0], s[1], fixed.has(i) ? 4 : 3, 0, 2 * Math.PI);
        ctx.fill();
      }
    }
  }

  // the other trace over the first: its cloth as a wire mesh, its spheres as rings
  function drawWire(ctx, x0, y0, w, h, frame, trace) {
    const {project: projectIn, focal} = projector(x0, y0, w, h);
    const p = positions[trace];
    const base = frame * floatsPerFrame;
    const project = (o) => projectIn(p, o);
    ctx.strokeStyle = 'rgba(200, 100, 20, 0.75)';
    ctx.lineWidth = 1;
    ctx.beginPath();
    if (cloth)
      for (const [a, b] of edges) {
        const sa = project(base + cloth.offset + 3 * a), sb = project(base + cloth.offset + 3 * b);
        if (!sa || !sb) continue;
        ctx.moveTo(sa[0], sa[1]);
        ctx.lineTo(sb[0], sb[1]);
      }
    ctx.stroke();
    if (spheres)
      for (let i = 0; i < spheres.count; ++i) {
        const s = project(base + spheres.offset + 3 * i);
        const r = data.sphere_radii[i] || 0;
        if (!s || !(r > 0)) continue;
        ctx.lineWidth = 2;
        ctx.beginPath();
        ctx.arc(s[0], s[1], (focal * r) / s[2], 0, 2 * Math.PI);
        ctx.stroke();
      }
  }

  function drawLabel(ctx, x, y, text, colour) {
    ctx.font = `${13 * devicePixelRatio}px system-ui, sans-serif`;
    ctx.fillStyle = colour;
    ctx.fillText(text, x + 8 * devicePixelRatio, y + 18 * devicePixelRatio);
  }

  function drawPlot() {
    if (!plot) return;
    const ctx = plot.getContext('2d');
    const w = plot.width, h = plot.height, s = devicePixelRatio;
    ctx.clearRect(0, 0, w, h);
    const left = 58 * s, right = w - 10 * s, top = 8 * s, bottom = h - 30 * s;
    let lo = Infinity, hi = 0;
    for (const v of differenceLargest)
      if (v > 0 && isFinite(v)) {
        lo = Math.min(lo, v);
        hi = Math.max(hi, v);
      }
    const firstS = differenceSteps[0], lastS = differenceSteps[differenceSteps.length - 1];
    const xOf = (step) => left + ((right - left) * (step - firstS)) / Math.max(1, lastS - firstS);
    ctx.strokeStyle = '#999';
    ctx.lineWidth = s;
    ctx.strokeRect(left, top, right - left, bottom - top);
    ctx.fillStyle = '#333';
    ctx.font = `${11 * s}px system-ui, sans-serif`;
    ctx.fillText('largest position difference (m), log scale', left + 4 * s, top + 12 * s);
    ctx.fillText(`step ${firstS}`, left, bottom + 14 * s);
    const lastText = `step ${lastS}`;
    ctx.fillText(lastText, right - ctx.measureText(lastText).width, bottom + 14 * s);
    if (hi > 0) {
      const e0 = Math.floor(Math.log10(lo)), e1 = Math.max(e0 + 1, Math.ceil(Math.log10(hi)));
      const yOf = (v) => (v > 0 ? bottom - ((bottom - top) * (Math.log10(v) - e0)) / (e1 - e0)
                                : bottom);
      for (let e = e0; e <= e1; e += Math.max(1, Math.ceil((e1 - e0) / 5))) {
        ctx.fillText(`1e${e}`, 6 * s, yOf(Math.pow(10, e)) + 4 * s);
        ctx.strokeStyle = '#eee';
        ctx.beginPath();
        ctx.moveTo(left, yOf(Math.pow(10, e)));
        ctx.lineTo(right, yOf(Math.pow(10, e)));
        ctx.stroke();
      }
      ctx.strokeStyle = '#1f5f9f';
      ctx.lineWidth = 1.5 * s;
      ctx.beginPath();
      for (let i = 0; i < differenceSteps.length; ++i) {
        const v = differenceLargest[i];
        const y = isFinite(v) ? yOf(v) : top;
        if (i === 0) ctx.moveTo(xOf(differenceSteps[i]), y);
        else ctx.lineTo(xOf(differenceSteps[i]), y);
      }
      ctx.stroke();
    } else {
      ctx.fillText('no difference at any common recorded step', left + 4 * s, (top + bottom) / 2);
    }
    if (firstStep !== null) {
      ctx.strokeStyle = '#d62728';
      ctx.setLineDash([4 * s, 3 * s]);
      ctx.beginPath();
      ctx.moveTo(xOf(firstStep), top);
      ctx.lineTo(xOf(firstStep), bottom);
      ctx.stroke();
      ctx.setLineDash([]);
    }
    ctx.strokeStyle = '#000';
    ctx.lineWidth = s;
    ctx.beginPath();
    ctx.moveTo(xOf(data.frame_steps[current]), top);
    ctx.lineTo(xOf(data.frame_steps[current]), bottom);
    ctx.stroke();
  }

  let current = 0;
  function draw() {
    const ctx = canvas.getContext('2d');
    const w = canvas.width, h = canvas.height;
    ctx.fillStyle = '#f4f6f8';
    ctx.fillRect(0, 0, w, h);
    if (frames === 0) return;
    if (two && layout === 'side') {
      for (let r = 0; r < 2; ++r) {
        ctx.save();
        ctx.beginPath();
        ctx.rect((r * w) / 2, 0, w / 2, h);
        ctx.clip();
        drawScene(ctx, (r * w) / 2, 0, w / 2, h, current, r, {wire: false});
        drawLabel(ctx, (r * w) / 2, 0, data.traces[r].label, '#222');
        ctx.restore();
      }
      ctx.fillStyle = '#bbb';
      ctx.fillRect(w / 2 - 1, 0, 2, h);
    } else {
      drawScene(ctx, 0, 0, w, h, current, 0, {wire: false});
      if (two) {
        drawWire(ctx, 0, 0, w, h, current, 1);
        drawLabel(ctx, 0, 0, `${data.traces[0].label} (shaded)`, '#1f4f8f');
        drawLabel(ctx, 0, 18 * devicePixelRatio, `${data.traces[1].label} (wire)`, '#a85a10');
      } else {
        drawLabel(ctx, 0, 0, data.traces[0].label, '#222');
      }
    }
    const t = frameT[current];
    timeLabel.textContent = `step ${data.frame_steps[current]} of ${data.traces[0].steps}` +
                            `, t = ${isFinite(t) ? t.toFixed(4) : t} s` +
                            ` (frame ${current + 1} of ${frames})`;
    slider.value = current;
    root.dataset.frame = String(current);
    drawPlot();
  }

  function resize() {
    const s = devicePixelRatio || 1;
    canvas.width = Math.max(1, Math.round(canvas.clientWidth * s));
    canvas.height = Math.max(1, Math.round(canvas.clientHeight * s));
    if (plot) {
      plot.width = Math.max(1, Math.round(plot.clientWidth * s));
      plot.height = Math.max(1, Math.round(plot.clientHeight * s));
    }
    draw();
  }

  function setFrame(i) {
    current = Math.max(0, Math.min(frames - 1, Math.round(i)));
    draw();
  }

  // ---- interaction ------------------------------------------------------------------------
  let playing = false, lastTick = 0;
  function tick(now) {
    if (!playing) return;
    if (now - lastTick >= 40) {  // 25 frames a second
      lastTick = now;
      if (current + 1 >= frames) {
        togglePlay();
        return;
      }
      setFrame(current + 1);
    }
    requestAnimationFrame(tick);
  }
  function togglePlay() {
    playing = !playing;
    playButton.textContent = playing ? '\u275A\u275A' : '\u25B6';
    if (playing) {
      if (current + 1 >= frames) setFrame(0);
      requestAnimationFrame(tick);
    }
  }
  playButton.addEventListener('click', togglePlay);
  backButton.addEventListener('click', () => setFrame(current - 1));
  nextButton.addEventListener('click', () => setFrame(current + 1));
  slider.addEventListener('input', () => setFrame(Number(slider.value)));
  root.addEventListener('keydown', (event) => {
    if (event.target === slider && event.key.startsWith('Arrow')) return;  // the slider's own
    if (event.key === ' ') togglePlay();
    else if (event.key === 'ArrowRight') setFrame(current + 1);
    else if (event.key === 'ArrowLeft') setFrame(current - 1);
    else return;
    event.preventDefault();
  });
  let drag = null;
  canvas.addEventListener('pointerdown', (event) => {
    drag = {x: event.clientX, y: event.clientY, yaw: camera.yaw, pitch: camera.pitch};
    canvas.setPointerCapture(event.pointerId);
  });
  canvas.addEventListener('pointermove', (event) => {
    if (!drag) return;
    camera.yaw = drag.yaw - (event.clientX - drag.x) * 0.01;
    camera.pitch = Math.max(-1.5, Math.min(1.5, drag.pitch + (event.clientY - drag.y) * 0.01));
    draw();
  });
  canvas.addEventListener('pointerup', () => (drag = null));
  canvas.addEventListener('wheel', (event) => {
    event.preventDefault();
    camera.distance *= Math.exp(event.deltaY * 0.001);
    draw();
  }, {passive: false});
  canvas.addEventListener('dblclick', () => {
    resetCamera();
    draw();
  });
  if (plot)
    plot.addEventListener('click', (event) => {
      // seek to the shown frame nearest the clicked step
      const box = plot.getBoundingClientRect();
      const s = devicePixelRatio;
      const fraction = ((event.clientX - box.left) * s - 58 * s) / (plot.width - 68 * s);
      const firstS = differenceSteps[0], lastS = differenceSteps[differenceSteps.length - 1];
      const step = firstS + fraction * (lastS - firstS);
      let best = 0;
      for (let i = 1; i < frames; ++i)
        if (Math.abs(data.frame_steps[i] - step) < Math.abs(data.frame_steps[best] - step)) best = i;
      setFrame(best);
    });
  window.addEventListener('resize', resize);
  resize();

  // stills: the run at a few times, both traces side by side in each (the grade report's strip)
  if (options.stills > 0 && frames > 0) {
    const strip = element('div', 'cv-stills');
    const count = Math.min(options.stills, frames);
    const s = devicePixelRatio || 1;
    for (let k = 0; k < count; ++k) {
      const frame = count > 1 ? Math.round((k * (frames - 1)) / (count - 1)) : 0;
      const figure = element('figure', 'cv-still');
      const still = element('canvas');
      still.width = Math.round(260 * s);
      still.height = Math.round(150 * s);
      figure.appendChild(still);
      const t = frameT[frame];
      figure.appendChild(element('figcaption', null,
          `t = ${isFinite(t) ? t.toFixed(4) : t} s (step ${data.frame_steps[frame]})` +
          (two ? `: ${data.traces[0].label} | ${data.traces[1].label}` : '')));
      const ctx = still.getContext('2d');
      ctx.fillStyle = '#f4f6f8';
      ctx.fillRect(0, 0, still.width, still.height);
      const parts = two ? 2 : 1;
      for (let r = 0; r < parts; ++r) {
        ctx.save();
        ctx.beginPath();
        ctx.rect((r * still.width) / parts, 0, still.width / parts, still.height);
        ctx.clip();
        drawScene(ctx, (r * still.width) / parts, 0, still.width / parts, still.height, frame, r,
                  {wire: false});
        ctx.restore();
      }
      strip.appendChild(figure);
    }
    root.insertBefore(strip, canvas);
  }

  const handle = {root, setFrame, frames, firstFrame, loadMs: performance.now() - started};
  clothrefViewers.push(handle);
  root.dataset.ready = '1';
  root.dataset.loadMs = handle.loadMs.toFixed(1);
  return handle;
}
