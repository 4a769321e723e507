import type { Connection } from 'vscode-languageserver/node';
import { ResponseError } from 'vscode-languageserver/node';
import { Flattener } from '../core/flatten';
import { refId } from '../core/sources';
import { EsminiRunResult, removeRunFolder, runScenario } from '../esmini/run';
import { RunEsminiParams, RunEsminiRequest, RunEsminiResult } from '../runProtocol';
import { Workspace } from '../workspace';
import { refOf, summarize } from './commands';

function stringList(value: unknown): string[] {
  return Array.isArray(value) ? value.filter((item): item is string => typeof item === 'string' && item.trim().length > 0) : [];
}

/**
 * "Run in esmini": flattens the file as the editor has it and runs it. The files of a file's
 * previous run are removed when it runs again, and all of them when the server exits.
 */
/** Run folders still on disk, of every server in this process; removed at exit (one listener for all). */
const liveRuns = new Set<EsminiRunResult>();
let exitListener = false;

export function register(connection: Connection, workspace: Workspace): void {
  const previous = new Map<string, EsminiRunResult>();
  if (!exitListener) {
    exitListener = true;
    process.on('exit', () => liveRuns.forEach(removeRunFolder));
  }

  connection.onRequest(RunEsminiRequest, async (params: RunEsminiParams, token): Promise<RunEsminiResult> => {
    try {
      const ref = await refOf(workspace, params?.uri);
      const duration = typeof params.duration === 'number' && params.duration > 0 && Number.isFinite(params.duration) ? params.duration : undefined;
      const cancel = new AbortController();
      token.onCancellationRequested(() => cancel.abort());
      const result = await runScenario(new Flattener(workspace.store), ref, {
        esminiPath: typeof params.esminiPath === 'string' ? params.esminiPath : undefined,
        roadPath: stringList(params.roadPath),
        base: workspace.folders[0],
        duration,
        cancel: cancel.signal,
      });
      const id = refId(ref);
      const earlier = previous.get(id);
      if (earlier) {
        removeRunFolder(earlier);
        liveRuns.delete(earlier);
      }
      previous.set(id, result);
      liveRuns.add(result);
      return {
        outcome: result.outcome,
        message: result.message,
        uri: workspace.uriOf(ref),
        problems: result.problems.map((problem) => ({
          uri: workspace.uriOf(problem.source),
          range: problem.range,
          severity: problem.severity,
          message: problem.message,
          count: problem.count,
          ...(problem.time !== undefined ? { time: problem.time } : {}),
          located: problem.located,
          ...(problem.note ? { note: problem.note } : {}),
        })),
        flattenProblems: result.flattenProblems.map((problem) => summarize(workspace, problem)),
        log: result.log,
        csvFile: result.csvFile,
        scenarioFile: result.scenarioFile,
        duration: result.duration,
        timeStep: result.timeStep,
        seed: result.seed,
        simulatedTime: result.simulatedTime,
        wallMs: result.wallMs,
        esmini: result.esmini,
        args: result.args,
      };
    } catch (error) {
      connection.console.error(`runEsmini failed: ${(error as Error)?.stack ?? String(error)}`);
      throw new ResponseError(-32603, `Run in esmini failed: ${(error as Error)?.message ?? String(error)}`);
    }
  });
}
