/** The extension's side of the page: messages to it, among them asking it to open a position in the source. */
import type { SourceLocation } from '../../../../common/src/sceneProtocol';
import type { FromView } from '../messages';

declare function acquireVsCodeApi(): { postMessage(message: FromView): void };
export const vscode = acquireVsCodeApi();

/** Asks the extension to show `source` in its editor. */
export const open = (source: SourceLocation | undefined) => source && vscode.postMessage({ type: 'open', source });
