// The e2e benchmark (not a test): `npx playwright test --config bench.config.js`. Same browser
// and flags as the tests; prints measurements with a baseline from the same run.
const base = require('./playwright.config.js');

module.exports = {
  ...base,
  testDir: './bench',
  testMatch: '*.bench.js',
  timeout: 900_000,
  reporter: [['list']],
  use: { ...base.use, viewport: { width: 1680, height: 1100 } },
};
