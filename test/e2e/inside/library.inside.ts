import * as assert from 'node:assert/strict';
import * as fs from 'node:fs';
import * as path from 'node:path';
import * as vscode from 'vscode';
import type { LibraryNode } from '../../../client/src/library/view';
import { pageShows, screenshot } from './harnessClient';
import { api, cli, type InsideTests, waitFor, workspaceRoot } from './helpers';

/** The module node the Scenario Library view shows for `name`, as its inline Insert button passes it. */
function moduleNode(name: string): LibraryNode {
  const tree = api().library.tree;
  for (const group of tree.getChildren())
    for (const node of tree.getChildren(group)) if (node.kind === 'module' && node.module.name === name) return node;
  assert.fail(`the Scenario Library view shows no module '${name}'`);
}

/** A main composed from the Scenario Library: a template, then three modules inserted from the view, then checked clean. */
export const libraryTests: InsideTests = {
  libraryCompose: async function () {
    this.timeout(180_000);
    const steps: string[] = [];
    await vscode.commands.executeCommand('modular2simple.library.focus');
    const tree = api().library.tree;
    await waitFor('the Scenario Library listing', () => (tree.current?.modules.length ?? 0) > 0, 60_000);
    assert.deepEqual(tree.current?.problems, [], 'the built-in library lists problems');
    await waitFor('the view drawing its modules', () => pageShows('library:cut-in'), 30_000);
    await screenshot('The Scenario Library view lists the modules by group');

    const folder = path.join(workspaceRoot(), 'composed');
    fs.mkdirSync(folder, { recursive: true });
    steps.push('New Scenario from Template… composition-bench');
    const created = await vscode.commands.executeCommand<vscode.Uri | undefined>(
      'modular2simple.newFromTemplate',
      vscode.Uri.file(folder),
      { template: 'composition-bench', fileName: 'composed.xosc' },
    );
    const main = path.join(folder, 'composed.xosc');
    assert.equal(created?.fsPath, main);
    await waitFor('the new main in the editor', () => vscode.window.activeTextEditor?.document.uri.fsPath === main, 30_000);

    const groups: string[] = [];
    for (const name of ['cut-in', 'lead-brake', 'pedestrian-crossing']) {
      steps.push(`Insert into Main: ${name}`);
      const group = await vscode.commands.executeCommand<string | undefined>('modular2simple.library.insert', moduleNode(name));
      assert.ok(group, `Insert into Main of ${name} wrote no group`);
      groups.push(group);
    }
    assert.equal(new Set(groups).size, 3, `group names repeat: ${groups.join(', ')}`);
    const document = await waitFor('the main in the editor', () =>
      vscode.window.activeTextEditor?.document.uri.fsPath === main ? vscode.window.activeTextEditor.document : undefined,
    );
    for (const name of ['cut-in', 'lead-brake', 'pedestrian-crossing'])
      assert.ok(document.getText().includes(`scenarioFileName="library:${name}"`), `no reference to library:${name}`);
    steps.push('Save');
    assert.ok(await document.save(), 'the main was not saved');

    // The server's view of the saved main: no error and no warning, as the CLI's check says too.
    await waitFor(
      'the server to analyse the composed main',
      async () =>
        ((await vscode.commands.executeCommand<unknown[]>('vscode.executeDocumentSymbolProvider', document.uri))?.length ?? 0) > 0 ||
        undefined,
      60_000,
    );
    await new Promise((resolve) => setTimeout(resolve, 2_000));
    const problems = vscode.languages
      .getDiagnostics(document.uri)
      .filter((diagnostic) => diagnostic.severity <= vscode.DiagnosticSeverity.Warning)
      .map((diagnostic) => `${diagnostic.range.start.line + 1}: ${diagnostic.message}`);
    assert.deepEqual(problems, []);
    cli(['check', main]);
    await screenshot('A main composed from three library modules, clean');
    assert.ok(steps.length <= 5, `composing took ${steps.length} steps: ${steps.join('; ')}`);
    console.log(`composed in ${steps.length} steps: ${steps.join('; ')}`);
  },
};
