import { CancellationToken, LSPErrorCodes, Position, ResponseError } from 'vscode-languageserver/node';
import {
  CheckInScenarioRunnerRequest,
  ExportForCarlaRequest,
  FlattenToFileRequest,
  FlattenToTextRequest,
  NewScenarioRequest,
  PackRequest,
  PreviewRequest,
  RunEsminiRequest,
  StructureRequest,
} from '../../../common/src/protocol';
import {
  LibraryCollisionsRequest,
  LibraryInsertRequest,
  LibraryModulesRequest,
  NewFromTemplateRequest,
  TemplatesRequest,
} from '../../../common/src/libraryProtocol';
import { RunTraceRequest, SceneRequest } from '../../../common/src/sceneProtocol';
import { SourceRef } from '../core/sources';
import { OpenDocument } from '../documents';
import { checkInScenarioRunner } from '../features/carlaCheck';
import { exportForCarlaToFile } from '../features/carlaExport';
import { codeActions } from '../features/codeActions';
import { diagnose } from '../features/diagnostics';
import { flattenToFile, flattenToText, structure } from '../features/commands';
import { complete } from '../features/completion';
import { definitionPlaces, toLocations } from '../features/definition';
import { distributionLenses } from '../features/distributions';
import { documentLinks } from '../features/documentLinks';
import { hover } from '../features/hover';
import { expressionHints } from '../features/inlayHints';
import { libraryCollisions, libraryInsert, libraryModules, newFromTemplate, templates } from '../features/library';
import { newScenario } from '../features/newScenario';
import { packCommand } from '../features/pack';
import { preview } from '../features/preview';
import { fileRenameEdits, placesToLocations, prepareRenameAt, referencesAt, renameAt } from '../features/references';
import { buildScene, runTrace } from '../features/scene';
import { semanticTokens } from '../features/semanticTokens';
import { codeLenses, documentSymbols, workspaceSymbols } from '../features/symbols';
import { Workspace } from '../workspace';
import { checkCancelled, openDocument, request, ServerContext } from './context';
import { formatDocument } from './formatting';

/** The answer about the open scenario document a request names; `none` when its URI is not one. */
function aboutOpen<P extends { textDocument: { uri: string } }, R>(
  context: ServerContext,
  none: R,
  answer: (open: OpenDocument, params: P, token: CancellationToken) => R | Promise<R>,
): (params: P, token: CancellationToken) => Promise<R> {
  return async (params, token) => {
    const open = await openDocument(context, params.textDocument.uri);
    return open ? answer(open, params, token) : none;
  };
}

/** A feature's answer about the position a request names in an open document; `none` when it names no open scenario. */
function atPosition<P extends { textDocument: { uri: string }; position: Position }, R>(
  context: ServerContext,
  none: R,
  feature: (workspace: Workspace, ref: SourceRef, offset: number) => R | Promise<R>,
): (params: P, token: CancellationToken) => Promise<R> {
  return aboutOpen(context, none, (open, params: P) => feature(context.workspace, open.ref, open.document.offsetAt(params.position)));
}

/** Waits for the first workspace index (a request about the whole workspace needs it), then checks cancellation. */
async function indexed(context: ServerContext, method: string, token: CancellationToken): Promise<void> {
  await context.indexed;
  checkCancelled(token, method);
}

/** Semantic tokens of an open document, whole or of a range. */
async function tokensOf(context: ServerContext, uri: string, range?: Parameters<typeof rangeOf>[1]) {
  const open = await openDocument(context, uri);
  const semantics = open ? (await context.workspace.source(open.ref)).semantics : undefined;
  if (!open || !semantics) return { data: [] };
  return range ? semanticTokens(semantics, ...rangeOf(open, range)) : semanticTokens(semantics);
}

/** A range of the protocol as document offsets. */
function rangeOf(
  open: OpenDocument,
  range: { start: { line: number; character: number }; end: { line: number; character: number } },
): [number, number] {
  return [open.document.offsetAt(range.start), open.document.offsetAt(range.end)];
}

/**
 * The requests whose handler says it all: find the open document, call a feature, check cancellation
 * between awaits. Each row registers one method, wrapped by `request` (handlers/context.ts: an exception
 * logged with its stack and answered as InternalError, a ResponseError passed through, a cancelled request
 * answered with RequestCancelled). A handler that does more is a module of its own (handlers/index.ts).
 */
export const REQUESTS: Record<string, (context: ServerContext, method: string) => void> = {
  // What a reference, group or key at the cursor resolves to.
  'textDocument/hover': (context, method) => context.connection.onHover(request(context, method, atPosition(context, null, hover))),
  // File names, group names, override keys and ScenarioReference snippets.
  'textDocument/completion': (context, method) =>
    context.connection.onCompletion(
      request(
        context,
        method,
        aboutOpen(context, [], (open, params) =>
          complete(context.workspace, open.ref, open.document, open.document.offsetAt(params.position)),
        ),
      ),
    ),
  // Where a file, group or key at the cursor is declared, across files and packages.
  'textDocument/definition': (context, method) =>
    context.connection.onDefinition(
      request(
        context,
        method,
        aboutOpen(context, [], async (open, params, token) => {
          const places = await definitionPlaces(context.workspace, open.ref, open.document.offsetAt(params.position));
          checkCancelled(token, method);
          return toLocations(context.workspace, places);
        }),
      ),
    ),
  // Every use of a group or file across the indexed workspace.
  'textDocument/references': (context, method) =>
    context.connection.onReferences(
      request(context, method, async (params, token) => {
        await indexed(context, method, token);
        const open = await openDocument(context, params.textDocument.uri);
        if (!open) return [];
        const places = await referencesAt(
          context.workspace,
          open.ref,
          open.document.offsetAt(params.position),
          params.context.includeDeclaration,
          () => checkCancelled(token, method),
        );
        return placesToLocations(context.workspace, places);
      }),
    ),
  // ManeuverGroup names (declarations or references) and parameters can be renamed.
  'textDocument/prepareRename': (context, method) =>
    context.connection.onPrepareRename(request(context, method, atPosition(context, null, prepareRenameAt))),
  // Renames a ManeuverGroup with every reference to it, across files.
  'textDocument/rename': (context, method) =>
    context.connection.onRenameRequest(
      request(context, method, async (params, token) => {
        await indexed(context, method, token);
        const open = await openDocument(context, params.textDocument.uri);
        if (!open) throw new ResponseError(LSPErrorCodes.RequestFailed, 'only ManeuverGroup and parameter names can be renamed');
        const offset = open.document.offsetAt(params.position);
        return renameAt(context.workspace, open.ref, offset, params.newName, () => checkCancelled(token, method));
      }),
    ),
  // Updates the scenarioFileName values that name a renamed file or folder.
  'workspace/willRenameFiles': (context, method) =>
    context.connection.workspace.onWillRenameFiles(
      request(context, method, async (params, token) => {
        await indexed(context, method, token);
        return fileRenameEdits(context.workspace, params.files);
      }),
    ),
  // ManeuverGroups of the whole indexed workspace by name.
  'workspace/symbol': (context, method) =>
    context.connection.onWorkspaceSymbol(
      request(context, method, async (params, token) => {
        await indexed(context, method, token);
        return workspaceSymbols(context.workspace, params.query);
      }),
    ),
  // Quick fixes for the server's own diagnostics, adding a group's missing keys, and the refactorings.
  'textDocument/codeAction': (context, method) =>
    context.connection.onCodeAction(
      request(
        context,
        method,
        aboutOpen(context, [], (open, params) =>
          codeActions(
            context.workspace,
            params.textDocument.uri,
            open.ref,
            open.document,
            params.range,
            params.context.diagnostics,
            params.context.only,
            context.client.edits,
            async () => (await diagnose(context.workspace, open.ref)).diagnostics,
          ),
        ),
      ),
    ),
  // The override counts above each ScenarioReference, opening the preview; a distribution's count and Run Variations.
  'textDocument/codeLens': (context, method) =>
    context.connection.onCodeLens(
      request(
        context,
        method,
        aboutOpen(context, [], async (open, params) => [
          ...(await distributionLenses(context.workspace, params.textDocument.uri, open.ref)),
          ...(await codeLenses(context.workspace, params.textDocument.uri, open.ref)),
        ]),
      ),
    ),
  // Each resolved scenarioFileName links to its file.
  'textDocument/documentLink': (context, method) =>
    context.connection.onDocumentLinks(
      request(
        context,
        method,
        aboutOpen(context, [], (open) => documentLinks(context.workspace, open.ref)),
      ),
    ),
  // The outline of one file.
  'textDocument/documentSymbol': (context, method) =>
    context.connection.onDocumentSymbol(
      request(
        context,
        method,
        aboutOpen(context, [], async (open) => {
          const source = await context.workspace.source(open.ref);
          return source.original ? documentSymbols(source.original.document) : [];
        }),
      ),
    ),
  // The evaluated value of every `${...}` in the visible range.
  'textDocument/inlayHint': (context, method) =>
    context.connection.languages.inlayHint.on(
      request(
        context,
        method,
        aboutOpen(context, [], async (open, params) => {
          const semantics = (await context.workspace.source(open.ref)).semantics;
          return semantics ? expressionHints(semantics, ...rangeOf(open, params.range)) : [];
        }),
      ),
    ),
  // `$name` and `${...}` told apart from literal values.
  'textDocument/semanticTokens/full': (context, method) =>
    context.connection.languages.semanticTokens.on(request(context, method, (params) => tokensOf(context, params.textDocument.uri))),
  'textDocument/semanticTokens/range': (context, method) =>
    context.connection.languages.semanticTokens.onRange(
      request(context, method, (params) => tokensOf(context, params.textDocument.uri, params.range)),
    ),
  // Format Selection: only the white space of the selected lines.
  'textDocument/rangeFormatting': (context, method) =>
    context.connection.onDocumentRangeFormatting(
      request(context, method, async (params) => {
        const document = context.workspace.documents.text(params.textDocument.uri);
        if (!document) return [];
        const range = { start: document.offsetAt(params.range.start), end: document.offsetAt(params.range.end) };
        return formatDocument(context, params.textDocument.uri, params.options, range);
      }),
    ),
  // The flattened scenario from the editor's text, for the live preview.
  [FlattenToTextRequest.method]: (context, method) =>
    context.connection.onRequest(
      FlattenToTextRequest,
      request(context, method, (params) => flattenToText(context.workspace, params?.uri, params?.options)),
    ),
  // Writes the flattened scenario atomically, never over one of its inputs.
  [FlattenToFileRequest.method]: (context, method) =>
    context.connection.onRequest(
      FlattenToFileRequest,
      request(
        context,
        method,
        (params) =>
          flattenToFile(context.workspace, params?.uri, params?.outputPath, {
            ...params?.options,
            outsideWorkspace: params?.outsideWorkspace,
          }),
        { writes: true },
      ),
    ),
  // Writes the scenario for CARLA's ScenarioRunner atomically, never over its input; the loss report comes back as problems.
  [ExportForCarlaRequest.method]: (context, method) =>
    context.connection.onRequest(
      ExportForCarlaRequest,
      request(
        context,
        method,
        (params) =>
          exportForCarlaToFile(context.workspace, params?.uri, params?.outputPath, { outsideWorkspace: params?.outsideWorkspace }),
        { writes: true },
      ),
    ),
  // The scenario exported into a private folder and loaded by ScenarioRunner's own code; what it raised comes back at its source line.
  [CheckInScenarioRunnerRequest.method]: (context, method) =>
    context.connection.onRequest(
      CheckInScenarioRunnerRequest,
      request(context, method, (params, token) => checkInScenarioRunner(context.workspace, params, token)),
    ),
  // Writes a .mosc of a folder (or main.xosc) with what it references, or of chosen files.
  [PackRequest.method]: (context, method) =>
    context.connection.onRequest(
      PackRequest,
      request(context, method, (params) => packCommand(context.workspace, params?.inputs, params?.outputPath, params?.selfContained), {
        writes: true,
      }),
    ),
  // The reference graph for the Show Structure view.
  [StructureRequest.method]: (context, method) =>
    context.connection.onRequest(
      StructureRequest,
      request(context, method, (params) => structure(context.workspace, params?.uri)),
    ),
  // The live preview's flattened text and the map from source lines to its lines.
  [PreviewRequest.method]: (context, method) =>
    context.connection.onRequest(
      PreviewRequest,
      request(context, method, (params) => preview(context.workspace, params)),
    ),
  // What the bird's-eye view draws of a scenario.
  [SceneRequest.method]: (context, method) =>
    context.connection.onRequest(
      SceneRequest,
      request(context, method, (params) => buildScene(context.workspace, context.roads, params)),
    ),
  // A run's log read as a storyboard trace of the scenario (the bird's-eye view's event times for a loaded run).
  [RunTraceRequest.method]: (context, method) =>
    context.connection.onRequest(
      RunTraceRequest,
      request(context, method, (params) => runTrace(context.workspace, params)),
    ),
  // Runs the editor's text of a scenario in esmini.
  [RunEsminiRequest.method]: (context, method) =>
    context.connection.onRequest(
      RunEsminiRequest,
      request(context, method, (params, token) => context.esminiRuns.run(params, token)),
    ),
  // The text of a new main scenario with an ego on a chosen road network.
  [NewScenarioRequest.method]: (context, method) =>
    context.connection.onRequest(
      NewScenarioRequest,
      request(context, method, (params) => newScenario(context.workspace, params)),
    ),
  // The modules of the scenario libraries, for the Scenario Library view.
  [LibraryModulesRequest.method]: (context, method) =>
    context.connection.onRequest(
      LibraryModulesRequest,
      request(context, method, () => libraryModules(context.workspace)),
    ),
  // Insert into main: the questions, then the edit that writes a module's group into an Act.
  [LibraryInsertRequest.method]: (context, method) =>
    context.connection.onRequest(
      LibraryInsertRequest,
      request(context, method, (params) => libraryInsert(context.workspace, params)),
    ),
  // After an insert: the main run headless in esmini, and which of its scripted actors touch.
  [LibraryCollisionsRequest.method]: (context, method) =>
    context.connection.onRequest(
      LibraryCollisionsRequest,
      request(context, method, (params) => libraryCollisions(context.workspace, params)),
    ),
  // New Scenario from Template: the templates, then the files of a new scenario (the client writes them).
  [TemplatesRequest.method]: (context, method) =>
    context.connection.onRequest(
      TemplatesRequest,
      request(context, method, () => templates()),
    ),
  [NewFromTemplateRequest.method]: (context, method) =>
    context.connection.onRequest(
      NewFromTemplateRequest,
      request(context, method, (params) => newFromTemplate(params)),
    ),
};
