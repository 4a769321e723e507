import * as vscode from 'vscode';
import { type ExtractGroupChoice, type ExtractGroupCommandArguments, type ExtractGroupResult } from '../../common/src/protocol';
import type { CommandReporter } from './commands';
import type { ServerCommandClient } from './languageClient';

function isPosition(value: unknown): value is { line: number; character: number } {
  const candidate = value as { line?: unknown; character?: unknown } | undefined;
  return typeof candidate?.line === 'number' && typeof candidate.character === 'number';
}

function isArguments(value: unknown): value is ExtractGroupCommandArguments {
  const candidate = value as Partial<ExtractGroupCommandArguments> | undefined;
  return typeof candidate?.uri === 'string' && isPosition(candidate.position) && Array.isArray(candidate.choices);
}

/** The pick list of attributes to list in `parameterAttributes`, the suggested ones picked; undefined when the user cancels. */
async function chooseAttributes(choices: ExtractGroupChoice[]): Promise<string[] | undefined> {
  type Item = vscode.QuickPickItem & { id: string };
  const items: Item[] = choices.map((choice) => ({
    id: choice.id,
    label: choice.label,
    description: `= ${choice.value}`,
    picked: choice.suggested,
  }));
  const picked = await vscode.window.showQuickPick(items, {
    canPickMany: true,
    title: 'Extract to a simple scenario: the attributes a main may set',
    placeHolder: 'Numbers, entity references and enumerations are chosen; each keeps its current value as default',
    matchOnDescription: true,
  });
  return picked?.map((item) => item.id);
}

/**
 * *Extract to a simple scenario…* (the code action's command): lets the user change the choice of
 * attributes, asks the server for the edit, applies it and opens the new simple scenario beside.
 */
export async function extractGroupCommand(
  server: ServerCommandClient,
  reporter: CommandReporter,
  args: unknown,
): Promise<ExtractGroupResult | undefined> {
  if (!isArguments(args)) {
    void vscode.window.showErrorMessage('Extract to a simple scenario: use the light bulb (Ctrl+.) on a ManeuverGroup.');
    return undefined;
  }
  const attributes = await chooseAttributes(args.choices);
  if (!attributes) return undefined;
  try {
    const result = await server.extractGroup({ uri: args.uri, position: args.position, attributes });
    const edit = await server.workspaceEdit(result.edit);
    if (!(await vscode.workspace.applyEdit(edit)))
      throw new Error('the editor did not apply the edit (the file may have changed meanwhile)');
    await vscode.window.showTextDocument(vscode.Uri.parse(result.uri), {
      viewColumn: vscode.ViewColumn.Beside,
      preview: false,
      preserveFocus: true,
    });
    return result;
  } catch (error) {
    await reporter.failure('Extract to a simple scenario', error);
    return undefined;
  }
}
