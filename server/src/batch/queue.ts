import type { BatchPlanView } from '../cli/batch';
import type { CliOutput } from '../cli/common';
import type { BatchIdentity } from './results';
import type { RunSettings } from './runConcrete';

export async function queueBatch(_url: URL, _plan: BatchPlanView, _identity: BatchIdentity, _results: string, options: { quiet: boolean; io: CliOutput; settings: RunSettings }): Promise<number> {
  options.io.err('modular2simple: error: --queue is not available yet');
  return 3;
}
