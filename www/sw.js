// The service worker: after one visit the app opens and analyses photos with no network.
//
// Network first, cache as the fallback: online, every file comes from the server as without a
// service worker (a new build is never hidden behind an old cache), and each response that
// arrives is stored; offline, the stored copy answers. The install step stores the files the
// app cannot start without (the page, its scripts, both wasm modules, the pattern database)
// and the shipped samples, so that one visit is enough even if the page was closed before it
// had fetched them all.
const CACHE = 'proctex';
const CORE = [
  './', 'index.html', 'style.css', 'main.js', 'worker.js', 'queue.js', 'suggest.js', 'images.js',
  'synthesis.js', 'refiner.js',
  'manifest.webmanifest',
  'icons/icon-192.png', 'icons/icon-512.png',
  'pkg/proctex_web.js', 'pkg/proctex_web_bg.wasm', 'pkg/proctex_worker.js',
  'pkg/proctex_worker_bg.wasm', 'pkg/patterns.ptxdb', 'samples/manifest.tsv',
];

async function precache() {
  const cache = await caches.open(CACHE);
  await cache.addAll(CORE);
  // The samples: the files named in the first column of their manifest.
  const tsv = await (await cache.match('samples/manifest.tsv')).text();
  const samples = tsv.split('\n').slice(1).map((l) => l.split('\t')[0]).filter((f) => f);
  await cache.addAll(samples.map((f) => `samples/${f}`));
}

self.addEventListener('install', (e) => {
  e.waitUntil(precache().then(() => self.skipWaiting()));
});

self.addEventListener('activate', (e) => {
  e.waitUntil(self.clients.claim());
});

self.addEventListener('fetch', (e) => {
  const req = e.request;
  if (req.method !== 'GET' || new URL(req.url).origin !== self.location.origin) return;
  e.respondWith((async () => {
    try {
      const res = await fetch(req);
      if (res.ok) {
        const copy = res.clone();
        caches.open(CACHE).then((c) => c.put(req, copy));
      }
      return res;
    } catch (err) {
      const hit = await caches.match(req, { ignoreSearch: true });
      if (hit) return hit;
      throw err;
    }
  })());
});
