export declare const START_DEFAULTS: Readonly<Record<string, string>>;
export declare function writeStartSettings(settingsFile: string, esminiSettings: Record<string, unknown>): Record<string, unknown>;
