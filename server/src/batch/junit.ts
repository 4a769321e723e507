import type { BatchRow } from './row';

/** Text for an XML attribute or element: the five characters XML reserves, and control characters it does not allow, replaced. */
function xml(text: string): string {
  return text
    .replace(/&/g, '&amp;')
    .replace(/</g, '&lt;')
    .replace(/>/g, '&gt;')
    .replace(/"/g, '&quot;')
    .replace(/'/g, '&apos;')
    .replace(/[\u0000-\u0008\u000b\u000c\u000e-\u001f]/g, '');
}

/**
 * The batch as JUnit XML, the format CI tools (GitLab, Jenkins, GitHub test reporters) read: one test case per
 * concrete scenario, named by its index and values; a run that fails its criteria is a `failure` (each criterion that
 * held), one that did not complete (status error or timeout) an `error` with esmini's message, a discarded
 * combination `skipped`, each with the row's reason. Its `time` is the simulated seconds (esmini's fixed step makes wall time meaningless here).
 */
export function junitXml(rows: readonly BatchRow[], parameterNames: string[], suite: string, criteria: string | undefined): string {
  let failures = 0;
  let errors = 0;
  let skipped = 0;
  const cases = rows.map((row) => {
    const values = parameterNames.map((name) => `${name}=${row.parameters[name] ?? ''}`).join(', ');
    const open = `    <testcase classname="${xml(suite)}" name="${xml(`#${row.index}${values ? ` ${values}` : ''}`)}" time="${row.end_time_s ?? 0}"`;
    if (row.status === 'discarded') {
      skipped++;
      return `${open}>\n      <skipped message="${xml(row.reason || row.message)}"/>\n    </testcase>`;
    }
    if (row.status === 'error' || row.status === 'timeout') {
      errors++;
      return `${open}>\n      <error type="${row.status}" message="${xml(row.reason || row.message)}"/>\n    </testcase>`;
    }
    if (row.verdict === 'fail') {
      failures++;
      const reasons = (row.failed ?? []).join('; ');
      return `${open}>\n      <failure type="criteria" message="${xml(reasons)}">${xml(`status ${row.status}: ${row.message}`)}</failure>\n    </testcase>`;
    }
    return `${open}/>`;
  });
  const counts = `tests="${rows.length}" failures="${failures}" errors="${errors}" skipped="${skipped}"`;
  const properties = criteria ? `\n    <properties><property name="fail-if" value="${xml(criteria)}"/></properties>` : '';
  return (
    `<?xml version="1.0" encoding="UTF-8"?>\n<testsuites name="modular2simple batch" ${counts}>\n` +
    `  <testsuite name="${xml(suite)}" ${counts}>${properties}\n${cases.join('\n')}\n  </testsuite>\n</testsuites>\n`
  );
}
