export declare function warmingRuns(examples: string, out: string): Record<string, string[][]>;
export declare function writeCliCodeCache(root: string, only?: string): Promise<void>;
