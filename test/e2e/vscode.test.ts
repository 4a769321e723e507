import * as assert from 'node:assert/strict';
import { spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import JSZip from 'jszip';
import type { Browser, Frame, Page } from 'playwright-core';
import {
  ARTIFACTS,
  HarnessEndpoint,
  Progress,
  buildInsideSuite,
  copyFolder,
  createProfile,
  installExtension,
  launchBrowser,
  missingTools,
  packageExtension,
  removeInsideSuite,
  requireE2e,
  startCodeServer,
  type CodeServer,
  type InsideResult,
  type Profile,
} from './harness';
import { PAGE_ACTION_MS, STALL_MS } from './limits';
import { repoRoot } from '../support/paths';
import { temporaryFolder } from '../support/temporaryDirectory';
import { HARNESS_ENV, INSIDE_TESTS } from './titles';
import { BIRDS_EYE_FILES, prepareBirdsEye } from './birdsEyeSetup';
import { prepareVariations } from './variationsSetup';

/** The example workspace, plus two packages the tests need: one nested in another, one broken. */
async function prepareWorkspace(profile: Profile, progress: Progress): Promise<string> {
  const workspace = path.join(profile.root, 'examples');
  copyFolder(path.join(repoRoot, 'examples'), workspace);
  const braking = fs.readFileSync(path.join(workspace, 'braking.mosc'));
  const brakingMain = await (await JSZip.loadAsync(braking)).file('main.xosc')?.async('string');
  assert.ok(brakingMain, 'examples/braking.mosc holds no main.xosc');
  const nested = new JSZip();
  nested.file(
    'main.xosc',
    brakingMain
      .replace('scenarioFileName="hard_brake.xosc"', 'scenarioFileName="braking.mosc"')
      .replace('maneuverGroupName="HardBrake"', 'maneuverGroupName="Brake.HardBrake"'),
  );
  nested.file('braking.mosc', braking);
  fs.writeFileSync(path.join(workspace, 'nested.mosc'), await nested.generateAsync({ type: 'uint8array', compression: 'DEFLATE' }));
  // A ZIP header followed by garbage: what a truncated download looks like.
  fs.writeFileSync(
    path.join(workspace, 'broken.mosc'),
    Buffer.concat([Buffer.from('PK\x03\x04'), Buffer.from('this is not the rest of a ZIP archive\n'.repeat(8))]),
  );
  prepareBirdsEye(workspace, (what) => progress.step(what));
  prepareVariations(workspace, BIRDS_EYE_FILES.roadFolder);
  return workspace;
}

async function frameHasText(frame: Frame, text: string, selector = 'body'): Promise<boolean> {
  try {
    // Page code is a string: this project's types do not include the DOM.
    return (await frame.evaluate(
      `[...document.querySelectorAll(${JSON.stringify(selector)})].some((element) => element.innerText.includes(${JSON.stringify(text)}))`,
    )) as boolean;
  } catch {
    return false;
  }
}

/** What the page shows, for the tests inside VS Code that check what a person sees. */
function servePage(endpoint: HarnessEndpoint, page: Page): void {
  endpoint.page = page;
  endpoint.routes.set('/findText', async (body) => {
    const { text, selector } = body as { text: string; selector?: string };
    for (const frame of page.frames()) if (await frameHasText(frame, text, selector)) return { found: true };
    return { found: false };
  });
  endpoint.routes.set('/tokenColors', async (body) => {
    const { words } = body as { words: string[] };
    return (await page.evaluate(`(() => {
      const spans = [...document.querySelectorAll('.monaco-editor .view-lines span span')];
      const colors = {};
      for (const word of ${JSON.stringify(words)}) {
        // Neighbouring tokens of one colour share a span, so '<' may lead a tag name.
        const span = spans.find((candidate) => (candidate.textContent || '').trim().replace(/^<\\/?/, '') === word);
        colors[word] = span ? getComputedStyle(span).color : null;
      }
      return colors;
    })()`)) as Record<string, string | null>;
  });
  endpoint.routes.set('/palette', async (body) => {
    const { title } = body as { title: string };
    await page.keyboard.press('F1');
    const input = page.locator('.quick-input-widget input');
    await input.waitFor({ state: 'visible', timeout: PAGE_ACTION_MS });
    await input.fill(`>${title}`);
    // Enter runs the focused row: wait until the filter has put this command there.
    await page
      .locator('.quick-input-list .monaco-list-row.focused')
      .filter({ hasText: title.split(': ').pop() ?? title })
      .waitFor({ timeout: PAGE_ACTION_MS });
    await page.keyboard.press('Enter');
    return {};
  });
  endpoint.routes.set('/figure', async (body) => {
    const { name, values } = body as { name: string; values: number[] };
    console.log(`    figure: ${name}: ${values.join(', ')}`);
    fs.appendFileSync(path.join(ARTIFACTS, 'figures.txt'), `${name}: ${values.join(', ')}\n`);
    return {};
  });
  endpoint.routes.set('/quickInput', async () => {
    // What the quick input (the command palette, a quick pick, the save dialog of a remote window) shows.
    return (await page.evaluate(`(() => {
      const widget = document.querySelector('.quick-input-widget');
      const visible = !!widget && widget.style.display !== 'none' && widget.offsetParent !== null;
      const input = widget ? widget.querySelector('input') : null;
      const title = widget ? widget.querySelector('.quick-input-title') : null;
      return { visible, value: input ? input.value : '', title: title ? title.textContent : '' };
    })()`)) as { visible: boolean; value: string; title: string };
  });
  endpoint.routes.set('/computedStyles', async (body) => {
    const { selectors, property } = body as { selectors: string[]; property: string };
    const values: (string | null)[] = selectors.map(() => null);
    for (const frame of page.frames()) {
      const found = (await frame
        .evaluate(
          `${JSON.stringify(selectors)}.map((selector) => { const element = document.querySelector(selector); return element ? getComputedStyle(element).getPropertyValue(${JSON.stringify(property)}) : null; })`,
        )
        .catch(() => [])) as (string | null)[];
      found.forEach((value, index) => {
        if (values[index] === null && value !== null && value !== undefined) values[index] = value;
      });
    }
    return { values };
  });
  endpoint.routes.set('/boxes', async (body) => {
    const { selector } = body as { selector: string };
    // Where each matching element is drawn (CSS px of its frame) with its text, from the first frame that has one.
    for (const frame of page.frames()) {
      const boxes = (await frame
        .evaluate(
          `[...document.querySelectorAll(${JSON.stringify(selector)})].map((element) => { const box = element.getBoundingClientRect(); return { left: box.left, top: box.top, right: box.right, bottom: box.bottom, text: element.innerText }; })`,
        )
        .catch(() => [])) as unknown[];
      if (boxes.length > 0) return { boxes };
    }
    return { boxes: [] };
  });
  endpoint.routes.set('/clickText', async (body) => {
    const { text } = body as { text: string };
    // Links and buttons in any frame: the package view is a webview, an iframe of its own.
    for (const frame of page.frames()) {
      const target = frame.locator('a, button').filter({ hasText: text }).first();
      if ((await target.count().catch(() => 0)) > 0) {
        await target.click({ timeout: PAGE_ACTION_MS });
        return { clicked: true };
      }
    }
    return { clicked: false };
  });
  endpoint.routes.set('/clickElement', async (body) => {
    const { selector, text } = body as { selector: string; text: string };
    // Any element, in any frame: a webview's rows are plain elements in an iframe of their own.
    for (const frame of page.frames()) {
      const target = frame.locator(selector).filter({ hasText: text }).first();
      if ((await target.count().catch(() => 0)) > 0) {
        await target.click({ timeout: PAGE_ACTION_MS });
        return { clicked: true };
      }
    }
    return { clicked: false };
  });
  endpoint.routes.set('/drag', async (body) => {
    // A mouse drag from one element to another, as a person does it: Chromium's HTML drag and drop, with its data.
    const { from, to } = body as { from: { selector: string; text: string }; to: { selector: string; text: string } };
    const source = page.locator(from.selector).filter({ hasText: from.text }).first();
    const target = page.locator(to.selector).filter({ hasText: to.text }).first();
    await source.dragTo(target, { timeout: PAGE_ACTION_MS });
    return {};
  });
  endpoint.routes.set('/type', async (body) => {
    const { text } = body as { text: string };
    await page.keyboard.type(text, { delay: 20 });
    return {};
  });
  // Another window in front, then VS Code's again: what switching windows does to the page.
  endpoint.routes.set('/switchWindow', async () => {
    const browser = page.context().browser();
    const other = await browser?.newPage();
    await other?.bringToFront();
    await page.evaluate('window.dispatchEvent(new Event("blur"))');
    await new Promise((resolve) => setTimeout(resolve, 300));
    await page.bringToFront();
    await page.evaluate('window.dispatchEvent(new Event("focus"))');
    await other?.close();
    return {};
  });
  endpoint.routes.set('/keys', async (body) => {
    const { keys } = body as { keys: string[] };
    for (const key of keys) await page.keyboard.press(key);
    return {};
  });
}

describe('the packaged extension in a real VS Code (code-server, headless Chromium)', function () {
  // Mocha's own limit only backs up the stall limit: the hook that waits resets it at every step.
  this.timeout(STALL_MS + 60_000);
  const results = new Map<string, InsideResult>();
  let exitCode: number | undefined;
  /** Why the tests inside VS Code did not finish, when they stalled. */
  let stall: string | undefined;
  let vsixEntries: string[] = [];
  let vsixFile: string | undefined;
  /** What the language server inside VS Code logged as errors (it appends them to a file the harness names). */
  let serverErrors = '';

  before(async function () {
    const missing = missingTools();
    if (missing) {
      if (requireE2e()) throw new Error(`M2S_REQUIRE_E2E=1 but the real-VS-Code tests cannot run: ${missing}`);
      console.log(`    skipped: ${missing}`);
      this.skip();
    }
    fs.rmSync(ARTIFACTS, { recursive: true, force: true });
    fs.mkdirSync(ARTIFACTS, { recursive: true });
    // Mocha fails a hook whose whole duration passed its limit even when it ended in time, so each step
    // moves the limit to the time spent so far plus the stall limit.
    const hookStarted = Date.now();
    const allowStall = (): void => void this.timeout(Date.now() - hookStarted + STALL_MS + 60_000);
    const progress = new Progress(allowStall);
    const profile = createProfile();
    const endpoint = new HarnessEndpoint((route) => progress.step(`the request ${route} from inside VS Code`));
    let server: CodeServer | undefined;
    let browser: Browser | undefined;
    let runner: { extensionPath: string; testsPath: string } | undefined;
    const automationLog: string[] = [];
    try {
      const workspace = await prepareWorkspace(profile, progress);
      progress.step('preparing the workspace');
      const vsix = packageExtension(profile.root);
      progress.step('packaging the extension');
      vsixEntries = Object.keys((await JSZip.loadAsync(fs.readFileSync(vsix))).files).filter((name) => !name.endsWith('/'));
      vsixFile = path.join(temporaryFolder('m2s-vsix-'), 'modular2simple.vsix');
      fs.copyFileSync(vsix, vsixFile);
      installExtension(profile, vsix);
      progress.step('installing the extension');
      runner = await buildInsideSuite(profile.root);
      progress.step('building the inside suite');
      await endpoint.start();
      server = await startCodeServer(profile, {
        MODULAR2SIMPLE_SERVER_ERROR_LOG: path.join(profile.root, 'server-errors.log'),
        [HARNESS_ENV.endpoint]: endpoint.url,
        [HARNESS_ENV.workspace]: workspace,
        [HARNESS_ENV.cli]: path.join(repoRoot, 'dist', 'cli.js'),
        [HARNESS_ENV.grep]: process.env[HARNESS_ENV.grep] ?? '',
      });
      progress.step('starting code-server');
      browser = await launchBrowser(profile);
      progress.step('launching Chromium');
      const page = await browser.newPage({ viewport: { width: 1440, height: 900 } });
      servePage(endpoint, page);
      const exited = new Promise<number>((resolve) => {
        void page.exposeFunction('codeAutomationExit', (code: number) => resolve(code));
      });
      await page.exposeFunction('codeAutomationLog', (type: string, args: unknown[]) => {
        automationLog.push(`[${type}] ${args.map((arg) => (typeof arg === 'string' ? arg : JSON.stringify(arg))).join(' ')}`);
      });
      const remote = (file: string): string => `vscode-remote://127.0.0.1:${server?.port}${file}`;
      const payload = JSON.stringify([
        ['extensionDevelopmentPath', remote(runner.extensionPath)],
        ['extensionTestsPath', remote(runner.testsPath)],
      ]);
      await page.goto(`${server.url}/?folder=${encodeURIComponent(workspace)}&payload=${encodeURIComponent(payload)}`);
      progress.step('loading VS Code in the page');
      const stalled = progress.stalled().then((why) => {
        stall = why;
        return -1;
      });
      const finished = endpoint.finished.then((failures) => (failures > 0 ? 1 : 0));
      exitCode = await Promise.race([exited, finished, stalled]);
      if (exitCode === -1) await page.screenshot({ path: path.join(ARTIFACTS, 'TIMEOUT.png') }).catch(() => undefined);
    } finally {
      progress.stop();
      allowStall();
      // Chromium may not answer a close on a loaded machine; Playwright ends it when this process exits.
      await Promise.race([browser?.close().catch(() => undefined), new Promise((resolve) => setTimeout(resolve, 30_000))]);
      await server?.stop();
      await endpoint.stop();
      if (runner) removeInsideSuite(runner.extensionPath);
      fs.writeFileSync(path.join(ARTIFACTS, 'extension-host.log'), automationLog.join('\n'));
      fs.writeFileSync(path.join(ARTIFACTS, 'harness.log'), endpoint.log.join('\n'));
      fs.writeFileSync(path.join(ARTIFACTS, 'code-server.log'), server?.log.join('') ?? '');
      const errorLog = path.join(profile.root, 'server-errors.log');
      serverErrors = fs.existsSync(errorLog) ? fs.readFileSync(errorLog, 'utf8') : '';
      const logs = path.join(profile.userData, 'logs');
      if (fs.existsSync(logs)) fs.cpSync(logs, path.join(ARTIFACTS, 'logs'), { recursive: true });
      fs.rmSync(profile.root, { recursive: true, force: true });
    }
    for (const result of endpoint.results) results.set(result.title, result);
  });

  for (const title of Object.values(INSIDE_TESTS)) {
    it(title, function () {
      const result = results.get(title);
      if (!result && process.env[HARNESS_ENV.grep]) this.skip();
      assert.ok(
        result,
        `did not run inside VS Code (exit code ${exitCode}${stall ? `, ${stall}` : ''}); see ${path.relative(repoRoot, ARTIFACTS)}/extension-host.log`,
      );
      if (result.state === 'pending') this.skip();
      if (result.state === 'failed') assert.fail(result.error);
    });
  }

  it("the .vsix holds the bundles and the manifest's assets, nothing else", () => {
    const extensionFiles = vsixEntries
      .filter((name) => name.startsWith('extension/'))
      .map((name) => name.slice('extension/'.length))
      .sort();
    const manifest = JSON.parse(fs.readFileSync(path.join(repoRoot, 'package.json'), 'utf8')) as {
      main: string;
      contributes: { grammars: { path: string }[]; languages: { configuration?: string; icon?: { light: string } }[] };
    };
    const needed = [
      manifest.main,
      'dist/server.js',
      'dist/birdsEye.js',
      // The CLI, which Run Variations runs (batch).
      'dist/cli.js',
      'dist/cli-main.js',
      // proj4js, required by the server and the CLI when an export meets a GeoPosition.
      'dist/proj4.js',
      'dist/variations.js',
      // The storyboard timeline's page (issue 29).
      'dist/timeline.js',
      // The debug adapter (issue 29), a process of its own, and the session its child runs.
      'dist/debugAdapter.js',
      'dist/debugSession.js',
      // The compiled OpenSCENARIO schemas the server reads, and the ASAM schemas with their licence note.
      'dist/openscenario-schemas.json',
      // The harness Check in CARLA ScenarioRunner runs with the user's Python.
      'server/python/scenario_runner_check.py',
      // The built-in scenario library that scenarioFileName="library:NAME" resolves in (issue 28).
      ...fs
        .readdirSync(path.join(repoRoot, 'library'), { recursive: true, withFileTypes: true })
        .filter((entry) => entry.isFile())
        .map((entry) =>
          path.posix.join(
            'library',
            path.relative(path.join(repoRoot, 'library'), path.join(entry.parentPath, entry.name)).split(path.sep).join('/'),
          ),
        ),
      ...fs.readdirSync(path.join(repoRoot, 'schemas')).map((file) => `schemas/${file}`),
      ...manifest.contributes.grammars.map((grammar) => grammar.path),
      ...manifest.contributes.languages.flatMap((language) => [language.configuration, language.icon?.light]),
    ]
      .filter((file): file is string => file !== undefined)
      .map((file) => path.posix.normalize(file));
    for (const file of needed) assert.ok(extensionFiles.includes(file), `${file} is missing from the .vsix`);
    const unexpected = extensionFiles.filter(
      (file) =>
        !needed.includes(file) &&
        !/^(package\.json|readme\.md|LICENSE(\.txt)?|client\/icons\/[\w-]+\.svg|dist\/cli-main\.js\.cache|dist\/node_modules\/(koffi|@koromix\/koffi-[\w-]+)\/.+)$/i.test(
          file,
        ),
    );
    assert.deepEqual(unexpected, [], 'the .vsix holds files that do not run');
  });

  it('the debug adapter in the .vsix loads koffi, the native module it calls esmini through', async () => {
    assert.ok(vsixFile, 'the .vsix was packaged');
    const unpacked = temporaryFolder('m2s-vsix-');
    const zip = await JSZip.loadAsync(fs.readFileSync(vsixFile));
    for (const [name, entry] of Object.entries(zip.files)) {
      if (entry.dir || !name.startsWith('extension/dist/')) continue;
      const target = path.join(unpacked, name);
      fs.mkdirSync(path.dirname(target), { recursive: true });
      fs.writeFileSync(target, await entry.async('nodebuffer'));
    }
    const probe = spawnSync(process.execPath, ['-e', "process.stdout.write(typeof require('koffi').load)"], {
      cwd: path.join(unpacked, 'extension', 'dist'),
      encoding: 'utf8',
      env: { ...process.env, NODE_PATH: '' },
    });
    assert.equal(probe.stdout, 'function', probe.stderr);
  });

  it('the language server logged no error', () => {
    assert.equal(serverErrors, '');
  });

  /** Each `[error]` line of a VS Code log with the stack lines that follow it. */
  function loggedErrors(log: string): { line: string; stack: string[] }[] {
    const errors: { line: string; stack: string[] }[] = [];
    for (const line of log.split('\n')) {
      if (/\[error\]/.test(line)) errors.push({ line, stack: [] });
      else if (/^\s+at /.test(line)) errors.at(-1)?.stack.push(line);
    }
    return errors;
  }

  /** An error thrown inside one of code-server's own extensions (its JSON language client logging after the host closed its channel, seen at load 22): not ours to fix. */
  function raisedByBuiltInExtension(stack: string[]): boolean {
    const frames = stack.filter((frame) => frame.includes('/lib/vscode/extensions/'));
    return frames.length > 0 && !stack.some((frame) => frame.includes('/extensions/modular2simple.'));
  }

  it('closing the window logs no error: no "Starting server failed", no failed deactivation', function () {
    const logs = path.join(ARTIFACTS, 'logs');
    if (!fs.existsSync(logs)) this.skip();
    const alarming: string[] = [];
    for (const entry of fs.readdirSync(logs, { recursive: true, withFileTypes: true })) {
      if (!entry.isFile()) continue;
      const file = path.join(entry.parentPath, entry.name);
      const text = fs.readFileSync(file, 'utf8');
      if (entry.name === 'Modular2Simple Language Server.log')
        for (const line of text.split('\n')) if (/Starting server failed|\[error\]/.test(line)) alarming.push(`${entry.name}: ${line}`);
      // The extension host's own log after the window asked it to end: what deactivating the extensions logged.
      if (entry.name === 'remoteexthost.log') {
        const closing = text.indexOf('Extension host terminating');
        if (closing < 0) continue;
        for (const { line, stack } of loggedErrors(text.slice(closing)))
          if (!raisedByBuiltInExtension(stack)) alarming.push(`${entry.name}: ${line}`);
      }
    }
    assert.deepEqual(alarming, []);
  });

  it('nothing else failed inside VS Code', () => {
    const failed = [...results.values()].filter(
      (result) => result.state === 'failed' && !Object.values(INSIDE_TESTS).includes(result.title as never),
    );
    assert.deepEqual(
      failed.map((result) => `${result.title}: ${result.error}`),
      [],
    );
    assert.equal(stall, undefined, 'the tests inside VS Code did not finish');
  });
});
