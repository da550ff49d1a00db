// Headless Chromium for the browser tests and benchmarks: Debian's chromium (or
// MESHVID_CHROMIUM) driven by npm's playwright-core, which then downloads no browser of its
// own, with WebGL2 on SwiftShader (no GPU needed).
import { createRequire } from 'node:module';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));

/** Launches the browser; resolves to playwright-core's Browser. */
export async function launchChromium() {
  const { chromium } = createRequire(path.join(here, 'package.json'))('playwright-core');
  return chromium.launch({
    executablePath: process.env.MESHVID_CHROMIUM ?? '/usr/bin/chromium',
    args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  });
}
