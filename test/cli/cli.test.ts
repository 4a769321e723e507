import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import JSZip from 'jszip';
import { firstDifference } from '../../server/src/core/equivalence';
import { isWellFormed, parseXml } from '../../server/src/core/xml';
import { outerGroup, overwritingManeuverCatalog, runCli, scenario, simpleGroup } from '../support/fixtures';
import { libraryDir, repoRoot, requireCorpus } from '../support/paths';
import { listFiles, temporaryWorkspace } from '../support/workspace';

function simpleWorkspace(extra: Record<string, string | Uint8Array> = {}, parameters: [string, string][] = [['value', '12']]) {
  return temporaryWorkspace({
    'simple.xosc': scenario(simpleGroup('Go')),
    'main.xosc': scenario(outerGroup('Car', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Go', parameters }] }])),
    ...extra,
  });
}

/** Runs a flatten that must fail, and asserts the message, exit code 1 and that nothing was written. */
function expectFailure(root: string, args: string[], message: RegExp) {
  const before = listFiles(root);
  const run = runCli(args, { cwd: root });
  assert.equal(run.status, 1, run.stderr);
  assert.match(run.stderr, message);
  assert.doesNotMatch(run.stderr, /\n\s+at .*\(.*:\d+:\d+\)/, 'no stack trace');
  assert.deepEqual(listFiles(root), before, 'nothing was written');
  return run;
}

describe('cli: usage and compatibility', () => {
  it('prints help and exits 0; wrong usage exits 2', () => {
    const help = runCli(['--help']);
    assert.equal(help.status, 0);
    assert.match(help.stdout, /-cxm\|--convert-xosc-into-mosc/);
    assert.match(help.stdout, /Exit codes:/);
    const wrong = runCli(['flatten']);
    assert.equal(wrong.status, 2);
    assert.match(wrong.stderr, /flatten needs an input/);
    assert.equal(runCli(['--bogus']).status, 2);
  });

  it('-cxm packs files and -cmx flattens the package, like flatten does', () => {
    const root = simpleWorkspace();
    const pack = runCli(['-cxm', 'main.xosc', 'simple.xosc', 'out.mosc'], { cwd: root });
    assert.equal(pack.status, 0, pack.stderr);
    const flat = runCli(['--convert-mosc-to-xosc', 'out.mosc', 'out.xosc'], { cwd: root });
    assert.equal(flat.status, 0, flat.stderr);
    const direct = runCli(['flatten', 'main.xosc'], { cwd: root });
    assert.equal(firstDifference(fs.readFileSync(path.join(root, 'out.xosc'), 'utf8'), direct.stdout), undefined);
    assert.match(direct.stdout, /<AbsoluteTargetSpeed value="12"\/>/);
  });

  it('flatten --out-dir writes one file per input', () => {
    const root = simpleWorkspace();
    fs.mkdirSync(path.join(root, 'out'));
    fs.mkdirSync(path.join(root, 'second'));
    fs.copyFileSync(path.join(root, 'main.xosc'), path.join(root, 'second', 'main.xosc'));
    fs.copyFileSync(path.join(root, 'simple.xosc'), path.join(root, 'second', 'simple.xosc'));
    const run = runCli(['flatten', '.', 'second', '--out-dir', 'out'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.deepEqual(fs.readdirSync(path.join(root, 'out')).sort(), [`${path.basename(root)}.xosc`, 'second.xosc']);
  });

  it('an output folder that does not exist is exit 3 (the output cannot be written), for --out-dir as for -o, and nothing is written', () => {
    const root = simpleWorkspace();
    const before = listFiles(root);
    const runs = [
      runCli(['flatten', '.', '-o', 'nowhere/out.xosc'], { cwd: root }),
      runCli(['flatten', '.', '--out-dir', 'nowhere'], { cwd: root }),
      runCli(['modularize', 'main.xosc', '--out-dir', 'nowhere/out'], { cwd: root }),
    ];
    for (const run of runs) {
      assert.equal(run.status, 3, run.stderr);
      assert.match(run.stderr, /nowhere.*does not exist/);
    }
    assert.deepEqual(listFiles(root), before, 'nothing was written');
  });

  it('check prints compiler-style lines and JSON for CI', () => {
    const root = simpleWorkspace({}, [['AbsoluteTargetSped.value', '1']]);
    const text = runCli(['check', '.'], { cwd: root });
    assert.equal(text.status, 1);
    assert.match(text.stderr, /^main\.xosc:\d+:\d+: error: key 'AbsoluteTargetSped\.value' matches no attribute/m);
    assert.match(text.stderr, /did you mean 'AbsoluteTargetSpeed\.value'\?/);
    const json = runCli(['check', '.', '--format', 'json'], { cwd: root });
    const report = JSON.parse(json.stdout) as { errors: number; problems: { file: string; line: number; code: string }[] };
    assert.equal(report.errors, 1);
    assert.equal(report.problems[0].code, 'unknown-key');
    assert.equal(report.problems[0].file, 'main.xosc');
  });

  it('check lists problems by file, then line and column, whatever order the files were named in', () => {
    const root = temporaryWorkspace({
      'simple.xosc': scenario(simpleGroup('Go')),
      'a.xosc': scenario(
        outerGroup('Car', 'car', [
          {
            file: 'simple.xosc',
            groups: [
              {
                name: 'Go',
                parameters: [
                  ['AbsoluteTargetSped.value', '1'],
                  ['RelativeDistanceConditon.value', '2'],
                ],
              },
            ],
          },
        ]),
      ),
      'b.xosc': scenario(
        outerGroup('Car', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Go', parameters: [['AbsoluteTargetSped.value', '1']] }] }]),
      ),
    });
    const text = runCli(['check', 'b.xosc', 'a.xosc'], { cwd: root });
    assert.equal(text.status, 1);
    const places = text.stderr
      .split('\n')
      .map((line) => /^([^:]+):(\d+):(\d+): /.exec(line))
      .filter((match): match is RegExpExecArray => match !== null)
      .map((match) => ({ file: match[1], line: Number(match[2]), column: Number(match[3]) }));
    const json = JSON.parse(runCli(['check', 'b.xosc', 'a.xosc', '--format', 'json'], { cwd: root }).stdout) as {
      problems: { file: string; line: number; column: number }[];
    };
    for (const listed of [places, json.problems.map(({ file, line, column }) => ({ file, line, column }))]) {
      assert.deepEqual(new Set(listed.map((place) => place.file)), new Set(['a.xosc', 'b.xosc']));
      const sorted = [...listed].sort((x, y) => (x.file < y.file ? -1 : x.file > y.file ? 1 : 0) || x.line - y.line || x.column - y.column);
      assert.deepEqual(listed, sorted);
    }
  });

  it("check prints each finding of a catalog entry used by a reference on a line of its own, with the entry's file:line:column, two of one catalog line too", () => {
    const catalog = overwritingManeuverCatalog({ used: ['e1', 'e2'] });
    const main = scenario(
      '<ManeuverGroup name="G" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"/><CatalogReference catalogName="ManeuverCatalog" entryName="used"/></ManeuverGroup>',
    ).replace(
      '  <Entities>',
      '  <CatalogLocations><ManeuverCatalog><Directory path="catalogs"/></ManeuverCatalog></CatalogLocations>\n  <Entities>',
    );
    const root = temporaryWorkspace({ 'main.xosc': main, 'catalogs/ManeuverCatalog.xosc': catalog });
    const run = runCli(['check', 'main.xosc', '--simulator', 'carla'], { cwd: root });
    const referenceLine = main.split('\n').findIndex((line) => line.includes('entryName="used"')) + 1;
    const columns = [...catalog.split('\n')[4].matchAll(/priority=/g)].map((match) => (match.index ?? 0) + 'priority="'.length + 1);
    const printed = run.stderr.split('\n');
    const findings = printed.flatMap((line, index) =>
      line.includes('ignores Event priority') ? [[line.slice(0, line.indexOf(': warning')), printed[index + 1]]] : [],
    );
    assert.deepEqual(
      findings.map(([where]) => where.replace(/:\d+$/, '')),
      [`main.xosc:${referenceLine}`, `main.xosc:${referenceLine}`],
      run.stderr,
    );
    assert.deepEqual(
      findings.map(([, note]) => note),
      columns.map((column) => `  ${path.join('catalogs', 'ManeuverCatalog.xosc')}:5:${column}: note: here in the catalog entry`),
      run.stderr,
    );
  });

  it('the examples check clean and flatten', () => {
    const run = runCli(['check', 'examples'], { cwd: repoRoot });
    assert.equal(run.status, 0, run.stderr);
    const flat = runCli(['flatten', 'examples'], { cwd: repoRoot });
    assert.equal(flat.status, 0, flat.stderr);
    assert.match(flat.stdout, /name="LeadVehicle\.Brake\.HardBrake"/);
  });

  it('stats prints the table and the totals', function () {
    requireCorpus(this);
    const run = runCli(['stats', libraryDir]);
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stdout, /total\s+10,810\s+21,243\s+49\.1 %/);
    const json = JSON.parse(runCli(['stats', libraryDir, '--format', 'json']).stdout) as { rows: unknown[] };
    assert.equal(json.rows.length, 31);
  });
});

describe('cli: stats reads scenarios as check does', () => {
  // The shared simple scenario lies outside the library, found only through the scenario path.
  const files = {
    'lib/cut/main.xosc': scenario(outerGroup('Car', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Go' }] }])),
    'shared/simple.xosc': scenario(simpleGroup('Go')),
  };

  it('--scenario-path and SCENARIO_PATH reach the references of the library, as check finds them', () => {
    const root = temporaryWorkspace(files);
    const without = runCli(['stats', 'lib'], { cwd: root, env: { SCENARIO_PATH: undefined } });
    assert.equal(without.status, 1, without.stdout);
    // It said '(1 errors; run 'modular2simple check')', naming nothing to check.
    assert.match(
      without.stderr,
      new RegExp(
        `cut: cannot be flattened \\(1 error; 'modular2simple check ${path.join(root, 'lib', 'cut', 'main.xosc').replace(/[.*+?^${}()|[\]\\]/g, '\\$&')}', with the options given here, lists it\\)`,
      ),
    );
    assert.equal(runCli(['check', 'lib', '--scenario-path', 'shared'], { cwd: root }).status, 0);
    const withOption = runCli(['stats', 'lib', '--scenario-path', 'shared', '--format', 'json'], {
      cwd: root,
      env: { SCENARIO_PATH: undefined },
    });
    assert.equal(withOption.status, 0, withOption.stderr);
    const stats = JSON.parse(withOption.stdout) as { rows: { scenario: string }[]; shared: { file: string }[] };
    assert.deepEqual(
      stats.rows.map((row) => row.scenario),
      ['cut'],
    );
    assert.deepEqual(
      stats.shared.map((item) => path.relative(root, item.file)),
      [path.join('shared', 'simple.xosc')],
    );
    const withEnvironment = runCli(['stats', 'lib'], { cwd: root, env: { SCENARIO_PATH: path.join(root, 'shared') } });
    assert.equal(withEnvironment.status, 0, withEnvironment.stderr);
    assert.match(withEnvironment.stdout, /^\s+1\s+cut\s/m);
  });

  it('--schema-version is refused with what to run instead (stats counts lines; check checks a schema)', () => {
    const root = temporaryWorkspace(files);
    for (const args of [
      ['stats', 'lib', '--schema-version', '1.2'],
      ['stats', 'lib', '--schema-version=off'],
    ]) {
      const run = runCli(args, { cwd: root });
      assert.equal(run.status, 2, run.stdout);
      assert.match(
        run.stderr,
        /stats counts lines and checks no schema, so --schema-version does not apply to it: run 'modular2simple check lib --schema-version V'/,
      );
    }
    assert.doesNotMatch(runCli(['stats', '--help']).stdout, /--schema-version/);
  });

  it('--root lets the mains search upward past the library, as check --root does; a missing folder is named', () => {
    // The shared simple scenario beside the library, found by the upward search from lib/cut only when it may go there.
    const root = temporaryWorkspace({ 'lib/cut/main.xosc': files['lib/cut/main.xosc'], 'simple.xosc': files['shared/simple.xosc'] });
    const options = { cwd: root, env: { SCENARIO_PATH: undefined } };
    const without = runCli(['stats', 'lib'], options);
    assert.equal(without.status, 1, without.stdout);
    assert.match(without.stderr, /cut: cannot be flattened/);
    assert.equal(runCli(['check', 'lib', '--root', '.'], options).status, 0);
    const withRoot = runCli(['stats', 'lib', '--root', '.', '--format', 'json'], options);
    assert.equal(withRoot.status, 0, withRoot.stderr);
    const stats = JSON.parse(withRoot.stdout) as { rows: { scenario: string }[]; shared: { file: string }[] };
    assert.deepEqual(
      stats.rows.map((row) => row.scenario),
      ['cut'],
    );
    assert.deepEqual(
      stats.shared.map((item) => path.relative(root, item.file)),
      ['simple.xosc'],
    );
    const missing = runCli(['stats', 'lib', '--root', 'nowhere'], options);
    assert.equal(missing.status, 1, missing.stdout);
    assert.match(missing.stderr, /--root nowhere: no such folder/);
    assert.match(runCli(['stats', '--help']).stdout, /--root DIR {16}where the search upward from a main's folder/);
  });

  it('--simulator, --carla and the writing options are refused with what to do instead, nothing printed on standard output', () => {
    const root = temporaryWorkspace(files);
    const refusals: [string[], RegExp][] = [
      [['--simulator', 'carla'], /--simulator does not apply to it: run 'modular2simple check lib --simulator S'/],
      [['--simulator=esmini'], /--simulator does not apply to it/],
      [['--carla', '0.9.15'], /--carla does not apply to it: run 'modular2simple check lib --simulator carla --carla R'/],
      [['-o', 'table.txt'], /stats writes no file, so -o\/--output does not apply to it: redirect its standard output/],
      [['--out-dir', 'out'], /--out-dir does not apply to it/],
      [['--force'], /--force does not apply to it/],
      [['--self-contained'], /--self-contained is pack's/],
      [['--include-scenario-path'], /--include-scenario-path is pack's/],
    ];
    for (const [options, message] of refusals) {
      const run = runCli(['stats', 'lib', '--scenario-path', 'shared', ...options], { cwd: root });
      assert.equal(run.status, 2, `${options.join(' ')}: ${run.stderr}`);
      assert.match(run.stderr, message);
      assert.equal(run.stdout, '', options.join(' '));
    }
    assert.deepEqual(fs.readdirSync(root).sort(), ['lib', 'shared']);
  });
});

describe('cli: every row of SPEC 7', () => {
  it('maneuverGroupName not in the source: error with file, line and the names that exist', () => {
    const root = temporaryWorkspace({
      'simple.xosc': scenario(simpleGroup('Go') + simpleGroup('Stop')),
      'main.xosc': scenario(outerGroup('Car', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Gone' }] }])),
    });
    expectFailure(
      root,
      ['flatten', 'main.xosc', '-o', 'out.xosc'],
      /main\.xosc:\d+:\d+: error: 'simple\.xosc' has no ManeuverGroup named 'Gone'; it has: Go, Stop/,
    );
  });

  it('key that matches no listed attribute: error with the closest key', () => {
    const root = simpleWorkspace({}, [['WorldPositon.x', '3']]);
    expectFailure(
      root,
      ['flatten', 'main.xosc', '-o', 'out.xosc'],
      /error: key 'WorldPositon\.x' matches no attribute[^\n]*\n\s+hint: did you mean 'WorldPosition\.x'\?/,
    );
  });

  it('listed attribute missing on its element: error "no default value"', () => {
    const root = temporaryWorkspace({
      'simple.xosc': scenario(simpleGroup('Go').replace('parameterAttributes="x, y"', 'parameterAttributes="x, y, h"')),
      'main.xosc': scenario(outerGroup('Car', 'car', [{ file: 'simple.xosc', groups: [{ name: 'Go', parameters: [['h', '3.14']] }] }])),
    });
    expectFailure(root, ['flatten', 'main.xosc', '-o', 'out.xosc'], /error: no default value: <WorldPosition> lists 'h'/);
  });

  it('outer group without EntityRef: error, no crash', () => {
    const root = temporaryWorkspace({
      'simple.xosc': scenario(simpleGroup('Go')),
      'main.xosc': scenario(outerGroup('Car', undefined, [{ file: 'simple.xosc', groups: [{ name: 'Go' }] }])),
    });
    expectFailure(root, ['flatten', 'main.xosc', '-o', 'out.xosc'], /error: ManeuverGroup 'Car' has no <Actors><EntityRef/);
  });

  it('two ScenarioReferences in one group: both imported, in document order', () => {
    const root = temporaryWorkspace({
      'a.xosc': scenario(simpleGroup('A')),
      'b.xosc': scenario(simpleGroup('B')),
      'main.xosc': scenario(
        outerGroup('Car', 'car', [
          { file: 'a.xosc', groups: [{ name: 'A' }] },
          { file: 'b.xosc', groups: [{ name: 'B' }] },
        ]),
      ),
    });
    const run = runCli(['flatten', 'main.xosc'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.ok(run.stdout.indexOf('"Car.A"') > 0 && run.stdout.indexOf('"Car.A"') < run.stdout.indexOf('"Car.B"'));
  });

  it('a ParameterReference with a third attribute: read by name', () => {
    const root = simpleWorkspace();
    const main = path.join(root, 'main.xosc');
    fs.writeFileSync(
      main,
      fs
        .readFileSync(main, 'utf8')
        .replace('<ParameterReference key="value" value="12"/>', '<ParameterReference note="x" value="12" key="value"/>'),
    );
    const run = runCli(['flatten', 'main.xosc'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stdout, /<AbsoluteTargetSpeed value="12"\/>/);
  });

  it('key without a dot that ends like a listed attribute (relay vs y): unknown key, no crash', () => {
    const root = simpleWorkspace({}, [['relay', '5']]);
    expectFailure(root, ['flatten', 'main.xosc', '-o', 'out.xosc'], /error: key 'relay' matches no attribute/);
  });

  it('DOCTYPE with an external entity: never resolved', () => {
    const secret = 'TOP-SECRET-CONTENT';
    const root = simpleWorkspace({ 'secret.txt': secret });
    const main = path.join(root, 'main.xosc');
    const text = fs
      .readFileSync(main, 'utf8')
      .replace('<OpenSCENARIO>', `<!DOCTYPE OpenSCENARIO [ <!ENTITY leak SYSTEM "file://${root}/secret.txt"> ]>\n<OpenSCENARIO>`)
      .replace('value="12"', 'value="&leak;"');
    fs.writeFileSync(main, text);
    const run = expectFailure(root, ['flatten', 'main.xosc', '-o', 'out.xosc'], /external entity '&leak;' is never resolved/);
    assert.ok(!run.stdout.includes(secret) && !run.stderr.includes(secret));
  });

  it('non-ASCII text under a POSIX locale: kept as UTF-8 (with a BOM accepted)', () => {
    const root = simpleWorkspace({}, [['value', 'Straße 東京 ✓']]);
    const main = path.join(root, 'main.xosc');
    fs.writeFileSync(main, '\uFEFF' + fs.readFileSync(main, 'utf8'));
    const run = runCli(['flatten', 'main.xosc', '-o', 'out.xosc'], { cwd: root, env: { LANG: 'C', LC_ALL: 'C' } });
    assert.equal(run.status, 0, run.stderr);
    assert.match(fs.readFileSync(path.join(root, 'out.xosc'), 'utf8'), /value="Straße 東京 ✓"/);
  });

  it('an existing tmp/ folder in the working directory: untouched', () => {
    const root = simpleWorkspace({ 'tmp/keep.txt': 'mine' });
    const run = runCli(['flatten', 'main.xosc', '-o', 'out.xosc'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.equal(fs.readFileSync(path.join(root, 'tmp', 'keep.txt'), 'utf8'), 'mine');
    assert.deepEqual(listFiles(root), ['main.xosc', 'out.xosc', 'simple.xosc', 'tmp/keep.txt']);
  });

  it('a missing input while packing: no output, clear error', () => {
    const root = simpleWorkspace();
    expectFailure(root, ['-cxm', 'main.xosc', 'simple.xosc', 'gone.xosc', 'out.mosc'], /gone\.xosc: no such file/);
    fs.rmSync(path.join(root, 'simple.xosc'));
    expectFailure(root, ['pack', '.', '-o', 'out.mosc'], /main\.xosc:\d+:\d+: error: cannot find 'simple\.xosc'/);
  });

  it('a cycle of packages (unpacked folders): error printing the whole cycle', () => {
    const root = temporaryWorkspace({
      'main.xosc': scenario(outerGroup('M', 'car', [{ file: 'a.mosc', groups: [{ name: 'A.X' }] }])),
      'a/main.xosc': scenario(outerGroup('A', 'car', [{ file: 'b.mosc', groups: [{ name: 'B.X' }] }])),
      'b/main.xosc': scenario(outerGroup('B', 'car', [{ file: 'a.mosc', groups: [{ name: 'A.X' }] }])),
    });
    expectFailure(root, ['flatten', 'main.xosc', '-o', 'out.xosc'], /reference cycle: a\/main\.xosc -> b\/main\.xosc -> a\/main\.xosc/);
  });

  it('a value holding <, & or ": escaped, output well-formed', () => {
    const root = simpleWorkspace({}, [['value', 'a &lt; b &amp;&amp; c &quot;q&quot;']]);
    const run = runCli(['flatten', 'main.xosc', '-o', 'out.xosc'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    const out = fs.readFileSync(path.join(root, 'out.xosc'), 'utf8');
    assert.ok(isWellFormed(parseXml(out)));
    assert.match(out, /value="a &lt; b &amp;&amp; c &quot;q&quot;"/);
  });

  it('a ZIP entry named ../x: refused, nothing extracted', async () => {
    const zip = new JSZip();
    zip.file('main.xosc', scenario(''));
    zip.file('../escape.xosc', scenario(''));
    const root = temporaryWorkspace({ 'evil.mosc': await zip.generateAsync({ type: 'uint8array' }) });
    expectFailure(
      root,
      ['flatten', 'evil.mosc', '-o', 'out.xosc'],
      /entry named '\.\.\/escape\.xosc' that points outside the package; it was refused/,
    );
    assert.ok(!fs.existsSync(path.join(path.dirname(root), 'escape.xosc')));
  });

  it('malformed XML: error with file, line and column', () => {
    const root = simpleWorkspace();
    const simple = path.join(root, 'simple.xosc');
    fs.writeFileSync(simple, fs.readFileSync(simple, 'utf8').replace('</Maneuver>', '</Maneuvre>'));
    expectFailure(
      root,
      ['flatten', 'main.xosc', '-o', 'out.xosc'],
      /simple\.xosc:\d+:\d+: error: end tag <\/Maneuvre> has no matching start tag/,
    );
  });

  it('failure midway: an existing output is untouched and no temporary files are left', () => {
    const root = simpleWorkspace({ 'out.xosc': 'previous output' }, [['nope', '1']]);
    expectFailure(root, ['flatten', 'main.xosc', '-o', 'out.xosc'], /error: key 'nope'/);
    assert.equal(fs.readFileSync(path.join(root, 'out.xosc'), 'utf8'), 'previous output');
    const unwritable = runCli(['flatten', 'main.xosc', '-o', 'no/such/folder/out.xosc', '--force'], { cwd: root });
    assert.equal(unwritable.status, 3);
    assert.match(unwritable.stderr, /cannot write the output/);
    assert.deepEqual(listFiles(root), ['main.xosc', 'out.xosc', 'simple.xosc']);
  });

  it('never writes over an input', () => {
    const root = simpleWorkspace();
    const before = fs.readFileSync(path.join(root, 'simple.xosc'), 'utf8');
    const run = runCli(['flatten', 'main.xosc', '-o', 'simple.xosc'], { cwd: root });
    assert.equal(run.status, 1);
    assert.match(run.stderr, /refusing to write .*simple\.xosc: it is an input/);
    assert.equal(fs.readFileSync(path.join(root, 'simple.xosc'), 'utf8'), before);
  });

  it('--force writes the output the original would have, reporting what was skipped', () => {
    const root = simpleWorkspace({}, [
      ['nope', '1'],
      ['value', '13'],
    ]);
    const run = runCli(['flatten', 'main.xosc', '-o', 'out.xosc', '--force'], { cwd: root });
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stderr, /warning: key 'nope' matches no attribute.*\(skipped: --force\)/);
    assert.match(fs.readFileSync(path.join(root, 'out.xosc'), 'utf8'), /<AbsoluteTargetSpeed value="13"\/>/);
  });
});
