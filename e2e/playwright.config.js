// Playwright runs Debian's Chromium with a software WebGPU adapter (SwiftShader): these are
// the flags that give a working adapter on machines without a GPU (see DEVELOPERS.md).
const { defineConfig } = require('@playwright/test');

const PORT = Number(process.env.PROCTEX_E2E_PORT || 8124);

module.exports = defineConfig({
  testDir: './tests',
  timeout: 180_000,
  expect: { timeout: 30_000 },
  workers: 1,
  // list for the log; json for scripts/test.sh's ten slowest tests (e2e/slowest.js).
  reporter: [['list'], ['json', { outputFile: '../target/e2e/results.json' }]],
  use: {
    baseURL: `http://127.0.0.1:${PORT}/`,
    viewport: { width: 1200, height: 800 },
    deviceScaleFactor: 1,
    launchOptions: {
      executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
      args: [
        '--no-sandbox', '--enable-unsafe-webgpu', '--enable-features=Vulkan',
        '--use-vulkan=swiftshader', '--use-gl=angle', '--use-angle=swiftshader',
        '--disable-quic', '--no-first-run', '--disable-background-networking',
        '--disable-component-update', '--disable-sync',
        // A fake camera (a test pattern) that needs no permission prompt.
        '--use-fake-device-for-media-stream', '--use-fake-ui-for-media-stream',
      ],
    },
  },
  webServer: {
    command: `python3 -m http.server ${PORT} --bind 127.0.0.1 --directory ../www`,
    url: `http://127.0.0.1:${PORT}/index.html`,
    reuseExistingServer: false,
    timeout: 30_000,
  },
});
