import type { CliOutput } from './common';

export async function workerCommand(_argv: string[], io: CliOutput): Promise<number> {
  io.err('modular2simple: error: worker is not available yet');
  return 3;
}
