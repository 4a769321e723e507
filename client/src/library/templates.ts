import * as fs from 'node:fs';
import * as vscode from 'vscode';
import type { CommandReporter } from '../commands';
import type { ServerCommandClient } from '../languageClient';
import { freeScenarioName, writeNewFiles } from '../naming';
import { newFilePath, optionsAmong, targetFolder } from '../newScenario';

const TITLE = 'New Scenario from Template';

/** What a caller (a test, a keybinding) may pass instead of being asked. */
export interface TemplateOptions {
  template?: string;
  /** The new scenario's file name, in the folder. */
  fileName?: string;
}

/**
 * *New Scenario from Template…*: a template of the library (a test protocol composed from library modules), a folder
 * and a file name; writes the scenario, its road beside it and its distribution when it has one, never over a file,
 * and opens the scenario.
 */
export async function newFromTemplateCommand(
  server: ServerCommandClient,
  reporter: CommandReporter,
  clicked: unknown,
  ...rest: unknown[]
): Promise<vscode.Uri | undefined> {
  const options = optionsAmong<TemplateOptions>([clicked, ...rest], ['template', 'fileName']);
  try {
    let template = options.template;
    if (!template) {
      const templates = await server.templates();
      const picked = await vscode.window.showQuickPick(
        templates.map((each) => ({
          label: each.title,
          description: each.name + (each.distribution ? ' (with a distribution)' : ''),
          detail: each.summary,
          name: each.name,
        })),
        { title: TITLE, placeHolder: 'A test scenario composed from library modules', matchOnDescription: true, matchOnDetail: true },
      );
      if (!picked) return undefined;
      template = picked.name;
    }
    const folder = await targetFolder(clicked, TITLE);
    if (!folder) return undefined;
    const target = await newFilePath(folder, options.fileName, {
      title: TITLE,
      prompt: `The new scenario, in ${folder}`,
      proposed: freeScenarioName(folder, fs.existsSync, template),
    });
    if (!target) return undefined;
    const { files } = await server.newFromTemplate(template, vscode.Uri.file(target));
    const written = await writeNewFiles(files);
    reporter.log(`${TITLE}: ${template} wrote ${written.join(', ')}`);
    const uri = vscode.Uri.file(target);
    await vscode.window.showTextDocument(uri, { preview: false });
    return uri;
  } catch (error) {
    void reporter.failure(TITLE, error);
    return undefined;
  }
}
