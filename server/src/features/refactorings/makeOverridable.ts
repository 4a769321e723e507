import { CodeActionKind } from 'vscode-languageserver/node';
import { groupOf, makeOverridableEdit } from '../../core/refactor/makeOverridable';
import { elementAt } from '../../core/xml';
import { documentEdit, Refactoring } from './refactoring';

export const MAKE_OVERRIDABLE_KIND = `${CodeActionKind.RefactorRewrite}.makeOverridable`;

/**
 * *Make overridable* on an attribute of an element inside a group of a simple scenario (a file that
 * lists `parameterAttributes` and imports nothing): lists the attribute in its element's `parameterAttributes`.
 */
export const makeOverridableRefactoring: Refactoring = {
  kind: MAKE_OVERRIDABLE_KIND,
  async actions(target) {
    const { model } = target;
    if (model.declarations.length === 0 || model.references.length > 0) return [];
    const element = elementAt(model.document, target.start);
    if (!element || target.start >= element.startTagEnd) return [];
    const attribute = element.attributes.find((candidate) => target.start >= candidate.nameStart && target.end <= candidate.valueEnd + 1);
    if (!attribute) return [];
    const group = groupOf(model.groups, element);
    if (!group) return [];
    // The outer group sets the group's name and its actor: listing those would mean nothing.
    if ((element === group.element && attribute.name === 'name') || (element === group.actor && attribute.name === 'entityRef')) return [];
    const edit = makeOverridableEdit(element, attribute);
    if (!edit) return [];
    return [
      { title: `Make '${element.name}.${attribute.name}' overridable`, kind: MAKE_OVERRIDABLE_KIND, edit: documentEdit(target, [edit]) },
    ];
  },
};
