/**
 * Run in a child process by the scaling tests: builds an input of the given kind and size, then
 * prints the best of three times of the operation, in milliseconds. The input is built outside the
 * timing; only the operation under test is timed.
 */
import * as fs from 'node:fs';
import * as os from 'node:os';
import * as path from 'node:path';
import JSZip from 'jszip';
import { Flattener } from '../../server/src/core/flatten';
import { childRef, diskRef, ScenarioStore } from '../../server/src/core/sources';
import { parseXml } from '../../server/src/core/xml';
import { outerGroup, scenario, simpleGroup } from './fixtures';

type Operation = () => Promise<void> | void;

async function nestedPackages(levels: number): Promise<Operation> {
  // Level k's main.xosc imports group Go from inner.mosc, which is level k+1.
  let inner: Uint8Array | undefined;
  for (let level = levels; level >= 0; level--) {
    const zip = new JSZip();
    if (inner) {
      // The imported group carries the names of every level below: Go, Go.Go, Go.Go.Go, ...
      const name = Array.from({ length: levels - level }, () => 'Go').join('.');
      zip.file('main.xosc', scenario(outerGroup('Go', 'car', [{ file: 'inner.mosc', groups: [{ name }] }])));
      zip.file('inner.mosc', inner);
    } else {
      zip.file('main.xosc', scenario(simpleGroup('Go')));
    }
    inner = await zip.generateAsync({ type: 'uint8array', compression: 'DEFLATE' });
  }
  const folder = fs.mkdtempSync(path.join(os.tmpdir(), 'm2s-scaling-'));
  const file = path.join(folder, 'outer.mosc');
  fs.writeFileSync(file, inner as Uint8Array);
  return async () => {
    const store = new ScenarioStore({ root: folder, scenarioPath: [], limits: { maxDepth: levels + 10, maxTotalBytes: 2 ** 31 } });
    const result = await new Flattener(store).analyze(childRef(diskRef(file), 'main.xosc'));
    if (result.source.dependencies.length < levels) throw new Error(`only ${result.source.dependencies.length} files were read`);
  };
}

async function build(kind: string, size: number): Promise<Operation> {
  switch (kind) {
    case 'attributes': {
      const text = '<r ' + Array.from({ length: size }, (_, i) => `a${i}="${i}"`).join(' ') + ' a0="again"/>';
      return () => {
        if (!parseXml(text).problems.some((problem) => /appears twice/.test(problem.message)))
          throw new Error('the duplicate was not found');
      };
    }
    case 'end-tags': {
      // End tags that match nothing, under a deep stack of open elements.
      const text = '<r>' + '<a>'.repeat(1999) + '</zz>'.repeat(size) + '</a>'.repeat(1999) + '</r>';
      return () => void parseXml(text);
    }
    case 'nested-packages':
      return nestedPackages(size);
    default:
      throw new Error(`unknown kind ${kind}`);
  }
}

async function main(): Promise<void> {
  const [kind, sizeText] = process.argv.slice(2);
  const operation = await build(kind, Number(sizeText));
  let best = Infinity;
  for (let run = 0; run < 3; run++) {
    const started = process.hrtime.bigint();
    await operation();
    best = Math.min(best, Number(process.hrtime.bigint() - started) / 1e6);
  }
  process.stdout.write(`${best}\n`);
}

main().catch((error) => {
  process.stderr.write(`${(error as Error).stack}\n`);
  process.exit(1);
});
