import { Severity } from '../problems';
import { defineDiagnostic, ProblemWording } from './definition';
import { QC } from './qcRules';

/** A finding of the XML parser (core/xml/), as it words it: an error where the file is not well-formed, a warning otherwise. */
export function xmlWording(severity: Severity, message: string): ProblemWording<'xml'> {
  return { severity, code: 'xml', message };
}

export const XML = defineDiagnostic({
  code: 'xml',
  rule: { description: 'The file is well-formed XML.', qcRule: QC.validXml },
  severity: 'error',
});
