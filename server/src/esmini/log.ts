/** One `[error]` or `[warn]` line of esmini's log. */
export interface EsminiLogMessage {
  level: 'error' | 'warn';
  /** Simulated time printed with it; undefined while the scenario is being loaded. */
  time: number | undefined;
  text: string;
  /** Zero-based line in the log. */
  logLine: number;
}

// esmini 3.6 CommonMini/logger.cpp prints `[<time>] [<level>] <message>`, the time empty while loading.
const LOG_LINE = /^\[([^\]]*)\] \[(error|warn)\] (.*)$/;

/**
 * Messages that say nothing about the scenario in a headless run (esmini 3.6): no 3D models without
 * a viewer, and notes about esmini's own sample roads.
 */
export const HARMLESS_MESSAGES: readonly RegExp[] = [/^3D model .* not located/, /Unsupported geo reference attr: \+no_defs/, /Unsupported object type: (guide-post|rail-pole)/];

export function parseEsminiLog(output: string): EsminiLogMessage[] {
  const messages: EsminiLogMessage[] = [];
  const lines = output.split(/\r?\n/);
  for (let index = 0; index < lines.length; index++) {
    const match = LOG_LINE.exec(lines[index]);
    if (!match) continue;
    // A fatal error comes as "Exception: <message>", after its own line when it had one ("Exception: [] [error] <message>").
    const text = match[3].replace(/^Exception: (\[[^\]]*\] \[\w+\] )?/, '').trim();
    if (HARMLESS_MESSAGES.some((pattern) => pattern.test(text))) continue;
    messages.push({ level: match[2] as 'error' | 'warn', time: match[1] === '' ? undefined : Number(match[1]), text, logLine: index });
  }
  return messages;
}
