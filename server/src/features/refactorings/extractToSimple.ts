import * as path from 'node:path';
import { CodeAction, CodeActionKind, ResponseError, ErrorCodes } from 'vscode-languageserver/node';
import { EXTRACT_GROUP_COMMAND, ExtractGroupCommandArguments, ExtractGroupResult } from '../../../../common/src/protocol';
import { ManeuverGroupInfo } from '../../core/model';
import { extractGroup, tunableAttributes } from '../../core/refactor/extractGroup';
import { RefactoringRefusal } from '../../core/refactor/refusal';
import { catalogParametersOf } from '../../core/modularize/catalogParameters';
import { diskRef, nodeFileSystem, refId } from '../../core/sources';
import { fileUri } from '../../uris';
import { cannotCreateFiles, createAndEdit, Refactoring, RefactoringTarget } from './refactoring';

export const EXTRACT_TO_SIMPLE_KIND = `${CodeActionKind.RefactorExtract}.simpleScenario`;

/** The group whose start tag holds the range, in a scenario on disk. */
function groupAtStartTag(target: RefactoringTarget): ManeuverGroupInfo | undefined {
  if (target.ref.entries.length > 0) return undefined;
  return target.model.groups.find((group) => target.start >= group.element.start && target.end <= group.element.startTagEnd);
}

function entityNames(target: RefactoringTarget): Set<string> {
  return new Set(target.model.entities.map((entity) => entity.name));
}

/** The edit of *Extract to a simple scenario* (the custom request's answer too); throws a ResponseError saying why not. */
export async function extractGroupEdit(target: RefactoringTarget, attributes: readonly string[] | undefined): Promise<ExtractGroupResult> {
  const refused = cannotCreateFiles(target.client);
  if (refused) throw new ResponseError(ErrorCodes.InvalidRequest, `Extract to a simple scenario: ${refused}`);
  const group = groupAtStartTag(target);
  if (!group) throw new ResponseError(ErrorCodes.InvalidParams, 'Extract to a simple scenario: no ManeuverGroup start tag at the position');
  const document = target.model.document;
  let extracted;
  try {
    extracted = await extractGroup({
      file: target.ref.disk,
      text: document.text,
      document,
      group,
      chosen: attributes,
      entityNames: entityNames(target),
      exists: async (file) => (await nodeFileSystem.kind(file)) !== undefined || target.workspace.documents.has(refId(diskRef(file))),
      catalogParameters: await catalogParametersOf(target.workspace.store, target.ref, target.model.document, [group.element]),
    });
  } catch (error) {
    if (error instanceof RefactoringRefusal)
      throw new ResponseError(ErrorCodes.InvalidRequest, `Extract to a simple scenario: ${error.message}`);
    throw error;
  }
  const uri = fileUri(extracted.file).toString();
  return {
    edit: createAndEdit(target, [{ uri, create: true, text: extracted.text, edits: [] }], [extracted.replacement]),
    uri,
    parameters: extracted.parameters,
  };
}

/**
 * *Extract to a simple scenario…* on a ManeuverGroup's start tag. A client with the pick list gets a
 * command (it asks for the edit once the user has chosen); any other the edit with the suggested choice.
 */
export const extractToSimpleRefactoring: Refactoring = {
  kind: EXTRACT_TO_SIMPLE_KIND,
  async actions(target) {
    const group = groupAtStartTag(target);
    if (!group) return [];
    const choices = tunableAttributes(target.model.document, group, entityNames(target));
    if (!choices) return [];
    const title = `Extract '${group.name}' to a simple scenario…`;
    const refused = cannotCreateFiles(target.client);
    if (refused) return [{ title, kind: EXTRACT_TO_SIMPLE_KIND, disabled: { reason: refused } }];
    const position = target.document.positionAt(group.element.start);
    if (target.client.extractPicker) {
      const args: ExtractGroupCommandArguments = { uri: target.uri, position, choices };
      return [{ title, kind: EXTRACT_TO_SIMPLE_KIND, command: { title, command: EXTRACT_GROUP_COMMAND, arguments: [args] } }];
    }
    let extracted: ExtractGroupResult;
    try {
      extracted = await extractGroupEdit(target, undefined);
    } catch (error) {
      if (error instanceof ResponseError) return [{ title, kind: EXTRACT_TO_SIMPLE_KIND, disabled: { reason: error.message } }];
      throw error;
    }
    const { edit, uri } = extracted;
    const action: CodeAction = {
      title: `${title.slice(0, -1)} (${decodeURIComponent(path.posix.basename(uri))})`,
      kind: EXTRACT_TO_SIMPLE_KIND,
      edit,
    };
    return [action];
  },
};
