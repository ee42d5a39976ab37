// CPU time of the browser's GPU process, read from Linux's /proc: on the software adapter
// (SwiftShader) the GPU process rasterises every repaint on the CPU cores that the analysis
// worker shares, so a repaint's cost is that process's CPU, not the frame's wall time.
const { execSync } = require('child_process');
const fs = require('fs');

const sleep = (ms) => new Promise((done) => setTimeout(done, ms));

// The pid of the Chromium GPU process (null where there is none or no /proc).
function gpuProcess() {
  try {
    const line = execSync('ps -eo pid,args').toString().split('\n')
      .find((l) => l.includes('--type=gpu-process'));
    return line ? parseInt(line.trim().split(/\s+/)[0], 10) : null;
  } catch {
    return null;
  }
}

// User + system CPU of `pid` in ms (clock ticks of 10 ms).
function cpuMs(pid) {
  const stat = fs.readFileSync(`/proc/${pid}/stat`, 'utf8');
  const fields = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
  return (parseInt(fields[11], 10) + parseInt(fields[12], 10)) * 10;
}

// The GPU process's CPU per call of `step` (an async function that draws one frame and waits
// for it), less its idle CPU over the same time; null without /proc. Each step is followed by
// a pause so that the process finishes the frame before the next.
async function gpuCpuPerFrame(step, frames) {
  const pid = gpuProcess();
  if (pid === null) return null;
  let c0 = cpuMs(pid);
  await sleep(2000);
  const idlePerMs = (cpuMs(pid) - c0) / 2000;
  c0 = cpuMs(pid);
  const t0 = Date.now();
  for (let i = 0; i < frames; i++) {
    await step();
    await sleep(300);
  }
  return (cpuMs(pid) - c0 - idlePerMs * (Date.now() - t0)) / frames;
}

// A WebGPU canvas over the whole page, cleared and presented once per `window.benchPresent()`
// (the baseline: what any WebGPU page's frame of that size costs); `window.benchPresentEnd()`
// removes it.
async function addBareCanvas(page) {
  await page.evaluate(async () => {
    const canvas = document.createElement('canvas');
    canvas.width = innerWidth;
    canvas.height = innerHeight;
    canvas.style = 'position: fixed; left: 0; top: 0; z-index: 10';
    document.body.appendChild(canvas);
    const device = await (await navigator.gpu.requestAdapter()).requestDevice();
    const context = canvas.getContext('webgpu');
    context.configure({ device, format: navigator.gpu.getPreferredCanvasFormat(), alphaMode: 'opaque' });
    window.benchPresent = () => new Promise((done) => {
      const encoder = device.createCommandEncoder();
      encoder.beginRenderPass({ colorAttachments: [{
        view: context.getCurrentTexture().createView(), loadOp: 'clear', storeOp: 'store',
        clearValue: { r: 0.95, g: 0.95, b: 0.95, a: 1 },
      }] }).end();
      device.queue.submit([encoder.finish()]);
      requestAnimationFrame(() => requestAnimationFrame(done));
    });
    window.benchPresentEnd = () => { canvas.remove(); device.destroy(); };
  });
}

module.exports = { gpuCpuPerFrame, addBareCanvas };
