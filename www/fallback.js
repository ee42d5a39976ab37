// The page without WebGPU: the app's canvas cannot start, but a photo can still be opened,
// dropped or pasted and analysed in the worker. Each analysis is shown as the CPU reference
// render of its params, with the photo-vs-model plots (radial spectrum, channel histograms)
// and the exports that need no GPU (params JSON, WGSL and GLSL shaders), and the app's lighting
// option (the photo's lighting gradient divided out before the analysis).

const message = document.getElementById('message');
const el = (tag, props = {}, text = '') => {
  const e = Object.assign(document.createElement(tag), props);
  if (text) e.textContent = text;
  return e;
};

// Builds the fallback panel in the message box. `ctx`: { openFile, download(name, text),
// exportShader(paramsJson, format), setLighting(on): the option set and the photo analysed
// again }.
export function startFallback(notice, ctx) {
  message.className = 'fallback';
  message.style.display = 'block';
  message.querySelector('.text').textContent = notice;
  const status = el('div', { id: 'fallback_status' });
  const error = el('div', { id: 'fallback_error', className: 'error-text' });
  const buttons = el('div', { className: 'buttons' });
  const button = (id, label, onclick) => {
    const b = el('button', { id, type: 'button' }, label);
    b.addEventListener('click', onclick);
    buttons.appendChild(b);
    return b;
  };
  let params = null;
  button('fallback_open', 'Open photo…', () => ctx.openFile());
  const exports = [
    button('fallback_json', 'Params JSON…', () => ctx.download('proctex-params.json', params)),
    button('fallback_wgsl', 'WGSL…', () => ctx.download('proctex-texture.wgsl',
      ctx.exportShader(params, 'wgsl'))),
    button('fallback_glsl', 'GLSL…', () => ctx.download('proctex-texture.glsl',
      ctx.exportShader(params, 'glsl'))),
  ];
  exports.forEach((b) => { b.disabled = true; });
  // The same option as the app's, with its words: off by default, since on evenly lit photos it
  // usually costs more than it gains.
  const lighting = el('input', { id: 'fallback_lighting', type: 'checkbox', disabled: true });
  lighting.addEventListener('change', () => {
    lighting.disabled = true; // until the photo's analysis with the option comes back
    ctx.setLighting(lighting.checked);
  });
  const option = el('label', {
    title: "Divide the photo's lighting gradient out before the analysis (the plane through " +
      'its log luminance): for a photo lit from one side, whose texture should not carry the ' +
      'light. On evenly lit photos it usually costs more than it gains, so it is off by default',
  });
  option.append(lighting, ' Even out lighting');
  buttons.appendChild(option);
  const plots = el('canvas', { id: 'cpu_plots', width: 384, height: 150 });
  plots.hidden = true;
  message.append(status, error, buttons, plots);
  return {
    // An analysis arrived: its report (JSON text) and the CPU preview's pixels.
    showResult(name, ms, reportJson, rgba, size) {
      const report = JSON.parse(reportJson);
      params = JSON.stringify(report.params);
      exports.forEach((b) => { b.disabled = false; });
      lighting.disabled = false;
      error.textContent = '';
      const model = report.params.model.pattern?.kind ?? report.params.model.kind;
      const evened = report.params.source?.flattened_lighting ? ', lighting evened out' : '';
      status.textContent = `${name}: analysed in ${Math.round(ms)} ms (${model} model${evened}). ` +
        'Below: its CPU reference rendering, and the photo (solid) against the model (dashed).';
      const canvas = document.getElementById('cpu_preview');
      canvas.width = size; canvas.height = size;
      canvas.getContext('2d').putImageData(
        new ImageData(new Uint8ClampedArray(rgba.buffer), size, size), 0, 0);
      canvas.hidden = false;
      drawPlots(plots, report.photo, report.model);
      plots.hidden = false;
    },
    showError(text) {
      error.textContent = text;
      lighting.disabled = params === null;
    },
  };
}

// Left: log10 power per quarter-octave ring, finest first; right: the RGB histograms.
function drawPlots(canvas, photo, model) {
  const g = canvas.getContext('2d');
  const { width: w, height: h } = canvas;
  g.fillStyle = '#222'; g.fillRect(0, 0, w, h);
  const half = w / 2 - 6;
  const line = (values, x0, y, dashed, colour) => {
    if (!values.length) return;
    g.setLineDash(dashed ? [4, 3] : []);
    g.strokeStyle = colour;
    g.beginPath();
    values.forEach((v, i) => {
      const x = x0 + (i / Math.max(1, values.length - 1)) * half;
      if (i === 0) g.moveTo(x, y(v)); else g.lineTo(x, y(v));
    });
    g.stroke();
  };
  const logs = (s) => s.map((v) => Math.log10(Math.max(v, 1e-12)));
  const all = [...logs(photo.spectrum), ...logs(model.spectrum)];
  const [lo, hi] = [Math.min(...all), Math.max(...all)];
  const ys = (v) => h - 12 - ((v - lo) / Math.max(1e-9, hi - lo)) * (h - 24);
  line(logs(photo.spectrum), 4, ys, false, '#ddd');
  line(logs(model.spectrum), 4, ys, true, '#ddd');
  const top = Math.max(...photo.histograms.flat(), ...model.histograms.flat(), 1e-9);
  const yh = (v) => h - 12 - (v / top) * (h - 24);
  ['#e55', '#5c5', '#58f'].forEach((colour, c) => {
    line(photo.histograms[c], w / 2 + 2, yh, false, colour);
    line(model.histograms[c], w / 2 + 2, yh, true, colour);
  });
  g.setLineDash([]);
  g.fillStyle = '#aaa'; g.font = '10px sans-serif';
  g.fillText('spectrum (fine → coarse)', 6, 10);
  g.fillText('histograms', w / 2 + 4, 10);
}
