import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import { firstDifference } from '../../server/src/core/equivalence';
import { runCli, scenario, simpleGroup } from '../support/fixtures';
import { listFiles, temporaryWorkspace } from '../support/workspace';

const FORMATTED = '<A>\n  <B x="1"/>\n</A>\n';
const MESSY = '<A>\n<B   x="1" />\n</A>';

function snapshot(root: string): Record<string, string> {
  const result: Record<string, string> = {};
  for (const file of listFiles(root)) result[file] = fs.readFileSync(path.join(root, file), 'latin1');
  return result;
}

describe('cli: format', () => {
  it('--check lists the files that would change, exits 1, and writes nothing', () => {
    const root = temporaryWorkspace({ 'messy.xosc': MESSY, 'sub/clean.xosc': FORMATTED, 'sub/other.txt': MESSY });
    const before = snapshot(root);
    const run = runCli(['format', '--check', '--indent', '2', root]);
    assert.equal(run.status, 1, run.stderr);
    assert.deepEqual(run.stdout.trim().split('\n'), [path.join(root, 'messy.xosc')]);
    assert.match(run.stderr, /1 of 2 files would be reformatted/);
    assert.deepEqual(snapshot(root), before);
  });

  it('--check exits 0 on formatted files', () => {
    const root = temporaryWorkspace({ 'clean.xosc': FORMATTED });
    const run = runCli(['format', '--check', path.join(root, 'clean.xosc')]);
    assert.equal(run.status, 0, run.stderr);
    assert.equal(run.stdout, '');
  });

  it('formats in place, keeps the file equivalent, and a second run changes nothing', () => {
    const text = scenario(simpleGroup('Go')).replace(/\n\s*/g, '\n');
    const root = temporaryWorkspace({ 'main.xosc': text, 'clean.xosc': FORMATTED.replace('  ', '    ') });
    const cleanTime = fs.statSync(path.join(root, 'clean.xosc')).mtimeMs;
    const run = runCli(['format', '--indent', '4', root]);
    assert.equal(run.status, 0, run.stderr);
    assert.match(run.stderr, /formatted 1 of 2 files/);
    const formatted = fs.readFileSync(path.join(root, 'main.xosc'), 'utf8');
    assert.notEqual(formatted, text);
    assert.match(formatted, /\n {4}<FileHeader/);
    assert.equal(firstDifference(text, formatted), undefined);
    assert.equal(fs.statSync(path.join(root, 'clean.xosc')).mtimeMs, cleanTime, 'an unchanged file is not rewritten');
    assert.deepEqual(listFiles(root), ['clean.xosc', 'main.xosc'], 'no temporary file is left');
    assert.equal(runCli(['format', '--check', '--indent', '4', root]).status, 0);
  });

  it('--width and --indent tab are applied', () => {
    const root = temporaryWorkspace({ 'a.xosc': '<A><B first="1" second="2"/></A>' });
    assert.equal(runCli(['format', '--indent', 'tab', '--width', '10', path.join(root, 'a.xosc')]).status, 0);
    assert.equal(fs.readFileSync(path.join(root, 'a.xosc'), 'utf8'), '<A>\n\t<B\n\t\tfirst="1"\n\t\tsecond="2"/>\n</A>\n');
  });

  it('writes nothing at all when one file is malformed, and names the file and line', () => {
    const root = temporaryWorkspace({ 'good.xosc': MESSY, 'bad.xosc': '<A>\n  <B>\n</A>\n' });
    const before = snapshot(root);
    const run = runCli(['format', root]);
    assert.equal(run.status, 1);
    assert.match(run.stderr, /bad\.xosc:2:3: error: .*not well-formed/);
    assert.match(run.stderr, /nothing was written/);
    assert.deepEqual(snapshot(root), before);
  });

  it('refuses a file that is not UTF-8 rather than rewriting its bytes', () => {
    const latin1 = Buffer.concat([Buffer.from('<A>\n<B v="'), Buffer.from([0xe9]), Buffer.from('"/>\n</A>')]);
    const root = temporaryWorkspace({ 'latin.xosc': latin1 });
    const run = runCli(['format', root]);
    assert.equal(run.status, 1);
    assert.match(run.stderr, /not UTF-8/);
    assert.deepEqual(fs.readFileSync(path.join(root, 'latin.xosc')), latin1);
  });

  it('keeps a byte-order mark', () => {
    const root = temporaryWorkspace({ 'bom.xosc': '\uFEFF' + MESSY });
    assert.equal(runCli(['format', '--indent', '2', root]).status, 0);
    const bytes = fs.readFileSync(path.join(root, 'bom.xosc'));
    assert.deepEqual([...bytes.subarray(0, 3)], [0xef, 0xbb, 0xbf]);
    assert.equal(bytes.subarray(3).toString('utf8'), FORMATTED);
  });

  it('reports wrong usage with exit code 2', () => {
    assert.equal(runCli(['format']).status, 2);
    assert.equal(runCli(['format', '--indent', 'three', 'a.xosc']).status, 2);
    assert.equal(runCli(['format', '--width', '0', 'a.xosc']).status, 2);
    assert.equal(runCli(['format', '--bogus', 'a.xosc']).status, 2);
    const missing = runCli(['format', '/nonexistent/x.xosc']);
    assert.equal(missing.status, 1);
    assert.match(missing.stderr, /no such file/);
  });
});
