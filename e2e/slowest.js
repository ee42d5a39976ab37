// Prints the slowest Playwright tests of a JSON report (the `json` reporter's file):
// `node slowest.js REPORT.json [N]`. scripts/test.sh calls it so that every CI log shows where
// the browser tests spend their time.
const fs = require('fs');

const [file, n = '10'] = process.argv.slice(2);
const report = JSON.parse(fs.readFileSync(file, 'utf8'));
const rows = [];
function walk(suite) {
  for (const spec of suite.specs || []) {
    for (const t of spec.tests || []) {
      for (const r of t.results || []) {
        rows.push({ ms: r.duration, status: r.status, title: `${spec.file}: ${spec.title}` });
      }
    }
  }
  for (const child of suite.suites || []) walk(child);
}
for (const s of report.suites || []) walk(s);
rows.sort((a, b) => b.ms - a.ms);
const total = rows.reduce((a, r) => a + r.ms, 0);
console.log(`\n== the ${Math.min(Number(n), rows.length)} slowest of ${rows.length} Playwright tests ` +
  `(sum of all tests ${(total / 60000).toFixed(1)} min)`);
for (const r of rows.slice(0, Number(n))) {
  console.log(`${(r.ms / 1000).toFixed(1).padStart(7)} s  ${r.status === 'passed' ? '' : `[${r.status}] `}${r.title}`);
}
