/**
 * Why a batch the editor ran (`modular2simple batch`) did not end well, in one line for a notification, from what the
 * CLI printed: its closing `modular2simple: error: …` block (runs that failed in esmini, each reason under it), the
 * criteria the runs failed, or else the first problem that stopped it before any run (`FILE:LINE:COL: error: …`).
 * Undefined when it printed none of these. `resultsCsv`: the batch's results.csv, named by `name` (a notification is no
 * place for a whole path).
 */
export function batchFailure(lines: readonly string[], resultsCsv?: { path: string; name: string }): string | undefined {
  const failure = firstFailure(lines);
  return resultsCsv && failure !== undefined ? failure.split(resultsCsv.path).join(resultsCsv.name) : failure;
}

function firstFailure(lines: readonly string[]): string | undefined {
  const closing = lines.findIndex((line) => /^modular2simple: (error: |\d+ runs? failed the criteria)/.test(line));
  if (closing >= 0) {
    const block = [lines[closing].replace(/^modular2simple: (error: )?/, '')];
    for (const line of lines.slice(closing + 1)) {
      if (!/^\s/.test(line)) break;
      block.push(line.trim());
    }
    return block.join(' ');
  }
  const problem = lines.find((line) => /: error: /.test(line));
  return problem?.replace(/^modular2simple: error: /, '');
}

/** How many runs of the batch the time limit stopped (status limit), from the CLI's summary line; undefined without one. */
export function limitedRuns(lines: readonly string[]): number | undefined {
  for (const line of lines) {
    const counted = /^\d+ runs? \(\d+ ok, (\d+) limit,/.exec(line);
    if (counted) return Number(counted[1]);
  }
  return undefined;
}

/** What `BatchIdentity`'s keys stand for, as the editor's question names them. */
const IDENTITY_WORDS: Record<string, string> = {
  scenarioSha256: "the scenario's text",
  distributionSha256: "the distribution's text",
  duration: 'the duration limit',
  sample: 'the sampling',
  seed: 'the sampling seed',
  esminiSeed: "esmini's seed",
  criteria: 'the criteria',
  distribution: 'the distribution file',
};

/**
 * When the CLI refused to write into a results folder holding another batch's results (`… holds another batch's
 * results (it differs in duration, scenarioSha256); use another --results folder`): how they differ, in words
 * ("it differs in the duration limit, the scenario's text"). Undefined when it did not refuse so.
 */
export function otherBatchInResults(lines: readonly string[]): string | undefined {
  for (const line of lines) {
    const refused = /holds another batch's results \((.*)\); use another --results folder$/.exec(line);
    if (!refused) continue;
    const differs = /^it differs in (.*)$/.exec(refused[1]);
    if (!differs) return 'its columns differ';
    return `it differs in ${differs[1]
      .split(', ')
      .map((key) => IDENTITY_WORDS[key] ?? key)
      .join(', ')}`;
  }
  return undefined;
}
