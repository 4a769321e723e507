export declare function buildPercent(logText: string): number | undefined;
export declare function buildEsmini(options: {
  buildScript: string;
  dest: string;
  report: (line: string) => void;
  pollMs?: number;
  quietMs?: number;
  signal?: AbortSignal;
}): Promise<string | undefined>;
