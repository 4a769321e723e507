// The generated scenario of the semantic benchmarks: 1,000 parameters and 1,000 expressions.

/** 1,000 root parameters (half of them expressions over earlier ones) and 1,000 attributes with expressions. */
export function parameterScenario() {
  const declarations = [];
  for (let i = 0; i < 1000; i++) {
    const value = i % 2 === 0 ? String(i) : `\${$P${i - 1} * 2 + ${i}}`;
    declarations.push(`    <ParameterDeclaration name="P${i}" parameterType="double" value="${value}"/>`);
  }
  const events = [];
  for (let i = 0; i < 1000; i++) {
    events.push(
      `          <Event name="E${i}" priority="overwrite"><Action name="A${i}"><AbsoluteTargetSpeed value="\${($P${i} + $P${(i * 7) % 1000}) / 3.6 + round($P${(i * 13) % 1000})}"/></Action></Event>`,
    );
  }
  return `<?xml version="1.0"?>
<OpenSCENARIO>
  <FileHeader revMajor="1" revMinor="2" date="2026-01-01T00:00:00" description="bench" author="bench"/>
  <ParameterDeclarations>
${declarations.join('\n')}
  </ParameterDeclarations>
  <Entities><ScenarioObject name="Ego"/></Entities>
  <Storyboard>
    <Story name="S"><Act name="A"><ManeuverGroup name="G" maximumExecutionCount="1"><Actors selectTriggeringEntities="false"><EntityRef entityRef="Ego"/></Actors>
        <Maneuver name="M">
${events.join('\n')}
        </Maneuver>
    </ManeuverGroup></Act></Story>
  </Storyboard>
</OpenSCENARIO>
`;
}
