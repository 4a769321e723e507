/**
 * Why a batch the editor ran (`modular2simple batch`) did not end well, in one line for a notification, from what the
 * CLI printed: its closing `modular2simple: error: …` block (runs that failed in esmini, each reason under it), the
 * criteria the runs failed, or else the first problem that stopped it before any run (`FILE:LINE:COL: error: …`).
 * Undefined when it printed none of these.
 */
export function batchFailure(lines: readonly string[]): string | undefined {
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
