import { CodeActionKind } from 'vscode-languageserver/node';
import { inlineEdits } from '../../core/refactor/inline';
import { documentEdit, Refactoring } from './refactoring';

export const INLINE_KIND = `${CodeActionKind.RefactorInline}.scenarioReference`;

/** *Inline* on a group that holds a ScenarioReference (its start tag or the reference): the group replaced by its flattened form. */
export const inlineRefactoring: Refactoring = {
  kind: INLINE_KIND,
  async actions(target) {
    const group = target.model.groups.find(
      (candidate) =>
        candidate.references.length > 0 &&
        ((target.start >= candidate.element.start && target.end <= candidate.element.startTagEnd) ||
          candidate.references.some((reference) => target.start >= reference.element.start && target.end <= reference.element.end)),
    );
    if (!group) return [];
    const flattener = target.workspace.flattener();
    const main = flattener.rendered(target.source);
    const edits = inlineEdits(main, group.element);
    const title = `Inline '${group.name}'`;
    if (!edits) return [{ title, kind: INLINE_KIND, disabled: { reason: 'the group cannot be flattened: see its problems' } }];
    return [{ title, kind: INLINE_KIND, edit: documentEdit(target, edits) }];
  },
};
