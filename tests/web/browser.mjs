// browser.mjs — what the browser viewer's test and screenshot script share: python3 -m
// http.server on loopback, and Debian's Chromium started headless through puppeteer-core (from
// .tools/, scripts/install-deps.sh) with WebGL2 on SwiftShader.

import { spawn } from 'node:child_process';
import { createRequire } from 'node:module';
import fs from 'node:fs';
import path from 'node:path';

const CHROMIUM = process.env.NUT_CHROMIUM ?? '/usr/bin/chromium';

// python3 -m http.server on a free loopback port; resolves to { url, stop }.
export function serve(directory) {
  return new Promise((resolve, reject) => {
    const server = spawn('python3', ['-u', '-m', 'http.server', '0', '--bind', '127.0.0.1', '--directory', directory],
      { stdio: ['ignore', 'pipe', 'pipe'] });
    let output = '';
    const timer = setTimeout(() => reject(new Error(`http.server did not start: ${output}`)), 10000);
    server.stdout.on('data', (data) => {
      output += data;
      const m = /port (\d+)/.exec(output);
      if (m) {
        clearTimeout(timer);
        resolve({ url: `http://127.0.0.1:${m[1]}/`, stop: () => server.kill() });
      }
    });
    server.on('exit', (code) => reject(new Error(`http.server exited (${code}): ${output}`)));
  });
}

export async function launch(source) {
  const require = createRequire(path.resolve(source, '.tools', 'package.json'));
  let puppeteer;
  try {
    puppeteer = require('puppeteer-core');
  } catch {
    throw new Error('puppeteer-core is not installed in .tools/ (scripts/install-deps.sh installs it)');
  }
  if (!fs.existsSync(CHROMIUM)) return { skip: `${CHROMIUM} is not installed` };
  try {
    const browser = await puppeteer.launch({
      executablePath: CHROMIUM,
      headless: true,
      protocolTimeout: 600000, // a SwiftShader frame of a large city can take seconds
      // SwiftShader: WebGL2 on the CPU, as llvmpipe gives the desktop viewer GL on the CPU.
      // sRGB output, so that the screenshot holds the bytes the page drew.
      args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--force-color-profile=srgb'],
    });
    return { browser };
  } catch (error) {
    return { skip: `Chromium cannot start: ${error.message.split('\n')[0]}` };
  }
}

// Opens a page in a viewport of `size` plus a margin, and waits until <body data-state> leaves
// loading and streaming; console lines go to `messages`. Returns the page.
export async function open(browser, url, size, messages) {
  const page = await browser.newPage();
  await page.setViewport({ width: size[0] + 20, height: size[1] + 20, deviceScaleFactor: 1 });
  page.on('console', (m) => messages.push(`${m.type()}: ${m.text()}`));
  page.on('pageerror', (e) => messages.push(`pageerror: ${e.message}`));
  await page.goto(url);
  await page.waitForFunction(() => !['loading', 'streaming'].includes(document.body.dataset.state), { timeout: 240000, polling: 200 });
  return page;
}
