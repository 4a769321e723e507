/** Why a refactoring does not apply where it was asked (an expected answer, not a failure). */
export class RefactoringRefusal extends Error {
  override readonly name = 'RefactoringRefusal';
}
