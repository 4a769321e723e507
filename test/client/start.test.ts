import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { buildEsmini, buildPercent } from '../../scripts/esminiBuild.mjs';
import { writeStartSettings } from '../../scripts/startSettings.mjs';
import { repoRoot } from '../support/paths';
import { waitUntil } from '../support/wait';
import { temporaryWorkspace } from '../support/workspace';

describe('npm start: the settings of the VS Code it opens', () => {
  it('turns auto-save off, so that the bundled examples change only when the user saves', () => {
    const settingsFile = path.join(temporaryWorkspace(), 'user-data', 'User', 'settings.json');
    writeStartSettings(settingsFile, { 'modular2simple.esmini.path': '/esmini/bin/esmini' });
    const written = JSON.parse(fs.readFileSync(settingsFile, 'utf8')) as Record<string, unknown>;
    assert.equal(written['files.autoSave'], 'off');
    assert.equal(written['modular2simple.esmini.path'], '/esmini/bin/esmini');
    assert.equal(written['workbench.startupEditor'], 'none');
  });

  it('turns it off in a profile written before, and keeps what the user set there since', () => {
    const settingsFile = path.join(temporaryWorkspace(), 'settings.json');
    fs.writeFileSync(settingsFile, JSON.stringify({ 'editor.fontSize': 15, 'telemetry.telemetryLevel': 'off' }));
    assert.equal(writeStartSettings(settingsFile, {})['files.autoSave'], 'off');
    fs.writeFileSync(settingsFile, JSON.stringify({ 'files.autoSave': 'onFocusChange' }));
    assert.equal(writeStartSettings(settingsFile, {})['files.autoSave'], 'onFocusChange');
    const written = JSON.parse(fs.readFileSync(settingsFile, 'utf8')) as Record<string, unknown>;
    assert.equal(written['files.autoSave'], 'onFocusChange');
  });

  it('is what start.mjs writes', () => {
    const script = fs.readFileSync(path.join(repoRoot, 'scripts', 'start.mjs'), 'utf8');
    assert.match(script, /import \{ writeStartSettings \} from '\.\/startSettings\.mjs'/);
    assert.match(script, /writeStartSettings\(path\.join\(userData, 'User', 'settings\.json'\), esminiSettings\)/);
    assert.doesNotMatch(script, /autoSave/);
  });
});

/** A stand-in for ../shared/esmini/build.sh in a fresh folder, which is also the build's DEST. */
function standInBuild(script: string): { dest: string; buildScript: string } {
  const dest = temporaryWorkspace();
  const buildScript = path.join(dest, 'build.sh');
  fs.writeFileSync(buildScript, script);
  return { dest, buildScript };
}

describe('npm start: building esmini after the editor is open', () => {
  it('reads how far make is from its log', () => {
    assert.equal(buildPercent('-- Configuring done\n'), undefined);
    assert.equal(buildPercent('[  3%] Building CXX object a.o\nwarning: [ 99%] quoted\n[ 42%] Building CXX object b.o\n'), 42);
    assert.equal(buildPercent('[100%] Built target esmini\n'), 100);
  });

  it('reports the build as make goes, then where esmini is; a failed build is told and yields no program', async function () {
    // Writes make's lines to DEST/build.log as it goes, then the program; make's 100 % comes right before it exits.
    const { dest, buildScript } = standInBuild(
      'set -e\nfor p in 5 25 26 60; do echo "[ $p%] Building CXX object x.o" >> "$1/build.log"; sleep 0.2; done\n' +
        'echo "[100%] Built target esmini" >> "$1/build.log"\n' +
        'if [ -n "$FAIL" ]; then exit 1; fi\nmkdir -p "$1/bin" && printf "#!/bin/sh\\n" > "$1/bin/esmini" && chmod +x "$1/bin/esmini"\n',
    );
    try {
      const lines: string[] = [];
      const program = await buildEsmini({ buildScript, dest, report: (line) => lines.push(line), pollMs: 20 });
      assert.equal(program, path.join(dest, 'bin', 'esmini'));
      const percents = lines.flatMap((line) => /esmini build: (\d+) %/.exec(line)?.[1] ?? []).map(Number);
      // One line per tenth passed (a poll may see 26 rather than 25 on a busy machine), never two in one tenth.
      assert.ok(percents.length >= 3 && percents[percents.length - 1] === 100, lines.join('\n'));
      percents
        .slice(1)
        .forEach((percent, index) => assert.ok(Math.floor(percent / 10) > Math.floor(percents[index] / 10), lines.join('\n')));
      assert.match(lines[lines.length - 1], /^esmini built in \d+ s: .*bin\/esmini$/);

      fs.rmSync(path.join(dest, 'bin'), { recursive: true });
      fs.rmSync(path.join(dest, 'build.log'));
      process.env.FAIL = '1';
      const failed: string[] = [];
      assert.equal(await buildEsmini({ buildScript, dest, report: (line) => failed.push(line), pollMs: 20 }), undefined);
      assert.match(failed[failed.length - 1], /^esmini did not build after \d+ s$/);
    } finally {
      delete process.env.FAIL;
      fs.rmSync(dest, { recursive: true, force: true });
    }
  });
  it('stopping npm start stops the build with everything it started (make and the compilers run in its group)', async function () {
    // Its "compiler" is a background sleep, as make's children are: it must end with the build.
    const { dest, buildScript } = standInBuild(
      'sleep 30 & echo $! > "$1/compiler.pid"\necho "[ 10%] Building CXX object x.o" >> "$1/build.log"\nwait\n',
    );
    // A killed process whose parent is gone may stay a zombie until something reaps it: that counts as ended.
    const running = (pid: number) => {
      try {
        return !/^\d+ \(.*\) Z/.test(fs.readFileSync(`/proc/${pid}/stat`, 'utf8'));
      } catch {
        return false;
      }
    };
    try {
      const stop = new AbortController();
      const lines: string[] = [];
      const built = buildEsmini({ buildScript, dest, report: (line) => lines.push(line), pollMs: 20, signal: stop.signal });
      await waitUntil(() => fs.existsSync(path.join(dest, 'compiler.pid')) && lines.length > 0, 'the stand-in build to start', 10_000);
      const compiler = Number(fs.readFileSync(path.join(dest, 'compiler.pid'), 'utf8'));
      assert.ok(running(compiler));
      stop.abort();
      assert.equal(await built, undefined);
      assert.match(lines[lines.length - 1], /^esmini build stopped after \d+ s/);
      await waitUntil(() => !running(compiler), 'the compiler to end with the build', 5_000);
    } finally {
      fs.rmSync(dest, { recursive: true, force: true });
    }
  });
});
