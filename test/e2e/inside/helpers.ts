import * as assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as path from 'node:path';
import JSZip from 'jszip';
import * as vscode from 'vscode';
import type { Modular2SimpleApi } from '../../../client/src/extension';
import type { StructureNode } from '../../../common/src/protocol';
import { HARNESS_ENV, type InsideTestKey } from '../titles';
import { pageShows, pressKeys, quickInput } from './harnessClient';

// What the tests inside VS Code share: where the workspace is, waiting, opening and editing files.

/** Tests of one feature by their key in INSIDE_TESTS; the suite (extension.inside.ts) runs them in its order. */
export type InsideTests = Partial<Record<InsideTestKey, (this: Mocha.Context) => Promise<void>>>;

export const EXTENSION_ID = 'modular2simple.modular2simple';

export function workspaceRoot(): string {
  const root = process.env[HARNESS_ENV.workspace];
  assert.ok(root, `${HARNESS_ENV.workspace} is not set`);
  return root;
}

/**
 * The longest a test waits for one thing by default. Generous: the suite must hold on a 2-core machine at a load
 * of 25, where VS Code, its extension host, the language server and Chromium share what is left of the cores.
 */
export const WAIT_MS = 60_000;

/**
 * A test's own mocha limit inside VS Code (a backstop: each of its waits has its own), for a test that waits for a
 * few things of WAIT_MS each; a test that runs a simulator or a batch on top has twice this.
 */
export const TEST_MS = 180_000;

export async function waitFor<T>(
  what: string,
  probe: () => T | undefined | false | Promise<T | undefined | false>,
  timeoutMs = WAIT_MS,
): Promise<T> {
  const deadline = Date.now() + timeoutMs;
  let last: unknown;
  while (Date.now() < deadline) {
    try {
      const value = await probe();
      if (value !== undefined && value !== false) return value;
    } catch (error) {
      last = error;
    }
    await new Promise((resolve) => setTimeout(resolve, 100));
  }
  throw new Error(`timed out after ${timeoutMs} ms waiting for ${what}${last ? ` (last error: ${(last as Error).message})` : ''}`);
}

/**
 * Waits until the page (any frame, or the elements matching `selector`) shows `text`. What the page shows follows the
 * extension's state later (a webview's postMessage, a notification, a tree refresh are all asynchronous): a test that
 * means "the page shows X" waits for the page, not for the state that leads to it.
 */
export async function waitForPage(text: string, selector?: string, timeoutMs = WAIT_MS): Promise<void> {
  await waitFor(`the page to show "${text}"${selector ? ` in ${selector}` : ''}`, () => pageShows(text, selector), timeoutMs);
}

export function api(): Modular2SimpleApi {
  const extension = vscode.extensions.getExtension<Modular2SimpleApi>(EXTENSION_ID);
  assert.ok(extension?.isActive, 'the extension is not active');
  return extension.exports;
}

/** Skips a test whose feature the language server does not offer yet (the server is built in parallel). */
export function requireServerFeature(context: Mocha.Context, feature: string, offered: boolean): void {
  if (!offered) {
    console.log(`skipped: the language server does not offer ${feature}`);
    context.skip();
  }
}

export function offersRequest(request: { method: string }): boolean {
  const experimental = api().serverCapabilities()?.experimental as { requests?: string[] } | undefined;
  return experimental?.requests?.includes(request.method) ?? false;
}

export async function open(relative: string): Promise<vscode.TextEditor> {
  const document = await vscode.workspace.openTextDocument(vscode.Uri.file(path.join(workspaceRoot(), relative)));
  return vscode.window.showTextDocument(document, { viewColumn: vscode.ViewColumn.One, preview: false });
}

export function positionOf(document: vscode.TextDocument, text: string, offsetInText = 0): vscode.Position {
  const index = document.getText().indexOf(text);
  assert.ok(index >= 0, `${path.basename(document.uri.path)} does not contain ${text}`);
  return document.positionAt(index + offsetInText);
}

export async function replaceText(document: vscode.TextDocument, from: string, to: string): Promise<void> {
  const start = positionOf(document, from);
  const edit = new vscode.WorkspaceEdit();
  edit.replace(document.uri, new vscode.Range(start, start.translate(0, from.length)), to);
  assert.ok(await vscode.workspace.applyEdit(edit), `could not replace ${from}`);
}

export async function revertAndClose(): Promise<void> {
  await vscode.commands.executeCommand('workbench.action.files.revert');
  await vscode.commands.executeCommand('workbench.action.closeAllEditors');
}

export function packageUri(...parts: string[]): vscode.Uri {
  return vscode.Uri.from({ scheme: 'mosc', path: path.posix.join(workspaceRoot(), ...parts) });
}

export async function zipEntries(file: string): Promise<Map<string, string>> {
  const zip = await JSZip.loadAsync(fs.readFileSync(file));
  const entries = new Map<string, string>();
  for (const entry of Object.values(zip.files)) if (!entry.dir) entries.set(entry.name, await entry.async('string'));
  return entries;
}

export function cli(args: string[]): void {
  const cliPath = process.env[HARNESS_ENV.cli];
  assert.ok(cliPath, `${HARNESS_ENV.cli} is not set`);
  execFileSync(process.execPath, [cliPath, ...args], { cwd: workspaceRoot(), env: { ...process.env, ELECTRON_RUN_AS_NODE: '1' } });
}

/** Waits for the save dialog to propose `name`, then accepts it with Enter, as a person does. */
export async function acceptSaveDialog(name: string): Promise<void> {
  await waitFor(`the save dialog proposing ${name}`, async () => {
    const shown = await quickInput();
    return (shown.visible && shown.value.endsWith(`/${name}`)) || undefined;
  });
  await pressKeys(['Enter']);
}

export function flattenTree(node: StructureNode): StructureNode[] {
  return [node, ...node.children.flatMap(flattenTree)];
}
