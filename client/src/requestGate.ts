import type { Middleware } from 'vscode-languageclient';

/**
 * The requests VS Code makes by itself, on focus, scrolling and cursor moves (the lightbulb's code
 * actions, lenses, links, inlay hints, tokens, the outline), answered as "nothing" while the language
 * server is not running. Forwarded then, the client's sendRequest would try to start the server again
 * and log "Request textDocument/codeAction failed: Starting server failed" on every window switch
 * while it restarts or after it failed; what the user asks for (completion, rename, commands) still
 * goes through and says why it failed.
 */
export function whileRunning(isRunning: () => boolean): Middleware {
  return {
    provideCodeActions: (document, range, context, token, next) => (isRunning() ? next(document, range, context, token) : undefined),
    provideCodeLenses: (document, token, next) => (isRunning() ? next(document, token) : undefined),
    provideDocumentLinks: (document, token, next) => (isRunning() ? next(document, token) : undefined),
    provideDocumentSymbols: (document, token, next) => (isRunning() ? next(document, token) : undefined),
    provideHover: (document, position, token, next) => (isRunning() ? next(document, position, token) : undefined),
    provideInlayHints: (document, viewPort, token, next) => (isRunning() ? next(document, viewPort, token) : undefined),
    provideDocumentSemanticTokens: (document, token, next) => (isRunning() ? next(document, token) : undefined),
    provideDocumentSemanticTokensEdits: (document, previousResultId, token, next) =>
      isRunning() ? next(document, previousResultId, token) : undefined,
    provideDocumentRangeSemanticTokens: (document, range, token, next) => (isRunning() ? next(document, range, token) : undefined),
  };
}
