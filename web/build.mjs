// Bundles the viewer (src/main.js + three.js) into one self-contained script for
// `globalvis view`, which inlines it into a <script> element of the page it writes.
// Usage: node build.mjs [OUTFILE]   (default: ../build/web/viewer.js)
import * as esbuild from 'esbuild';
import { readFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const outfile = resolve(process.argv[2] || resolve(here, '../build/web/viewer.js'));
await esbuild.build({
  entryPoints: [resolve(here, 'src/main.js')],
  outfile,
  bundle: true,
  format: 'iife',
  minify: true,
  target: 'es2020',
  legalComments: 'eof',
  logLevel: 'warning',
});
// The page inlines the bundle, so it must not close its own <script> element.
if (/<\/script/i.test(readFileSync(outfile, 'utf8'))) {
  console.error(`${outfile}: contains "</script", cannot be inlined`);
  process.exit(1);
}
console.log(`viewer bundle: ${outfile}`);
