import { ContentAutomaton } from './automaton';
import {
  AttributeDeclaration,
  CompiledSchema,
  ComplexType,
  ElementParticle,
  elementParticles,
  SCHEMA_VERSIONS,
  schemaFor,
  SchemaVersion,
  SimpleType,
} from './model';
import { MODULAR_PLACEMENT, MODULAR_SIMPLE_TYPES, MODULAR_TYPES } from './modular';

/** One version's schema with the lookups validation and completion need, built once per version. */
export class SchemaIndex {
  private readonly automata = new Map<string, ContentAutomaton>();
  private readonly children = new Map<string, Map<string, ElementParticle>>();
  private readonly attributes = new Map<string, Map<string, AttributeDeclaration>>();

  constructor(readonly schema: CompiledSchema) {}

  get version(): SchemaVersion {
    return this.schema.version;
  }

  complexType(name: string): ComplexType | undefined {
    return this.schema.complexTypes[name] ?? MODULAR_TYPES[name];
  }

  simpleType(name: string): SimpleType | undefined {
    return this.schema.simpleTypes[name] ?? MODULAR_SIMPLE_TYPES[name];
  }

  /** The particle of a child element of a type; with `modular`, a ScenarioReference in a ManeuverGroup too. */
  childParticle(typeName: string, childName: string, modular: boolean): ElementParticle | undefined {
    if (modular && typeName === MODULAR_PLACEMENT.parentType && childName === MODULAR_PLACEMENT.element) return SCENARIO_REFERENCE_PARTICLE;
    let byName = this.children.get(typeName);
    if (!byName) {
      byName = new Map();
      for (const particle of elementParticles(this.complexType(typeName)?.content))
        if (!byName.has(particle.name)) byName.set(particle.name, particle);
      this.children.set(typeName, byName);
    }
    return byName.get(childName);
  }

  childParticles(typeName: string): ElementParticle[] {
    return elementParticles(this.complexType(typeName)?.content);
  }

  attribute(typeName: string, attributeName: string): AttributeDeclaration | undefined {
    let byName = this.attributes.get(typeName);
    if (!byName) {
      byName = new Map((this.complexType(typeName)?.attributes ?? []).map((declaration) => [declaration.name, declaration]));
      this.attributes.set(typeName, byName);
    }
    return byName.get(attributeName);
  }

  automaton(typeName: string): ContentAutomaton {
    let automaton = this.automata.get(typeName);
    if (!automaton) {
      automaton = new ContentAutomaton(this.complexType(typeName)?.content);
      this.automata.set(typeName, automaton);
    }
    return automaton;
  }

  /** The name the content model sees for a child: a ScenarioReference takes a Maneuver's place. */
  modelName(typeName: string, childName: string, modular: boolean): string {
    return modular && typeName === MODULAR_PLACEMENT.parentType && childName === MODULAR_PLACEMENT.element
      ? MODULAR_PLACEMENT.standsFor
      : childName;
  }

  /** Whether a complex type's element (by particle) is deprecated in this version. */
  isDeprecated(particle: ElementParticle): boolean {
    return Boolean(particle.deprecated || this.complexType(particle.type)?.deprecated);
  }

  isAttributeDeprecated(declaration: AttributeDeclaration): boolean {
    return Boolean(declaration.deprecated || this.simpleType(declaration.type)?.deprecated);
  }
}

const SCENARIO_REFERENCE_PARTICLE: ElementParticle = {
  kind: 'element',
  name: MODULAR_PLACEMENT.element,
  type: MODULAR_PLACEMENT.type,
  min: 0,
  max: -1,
};

const indexes = new Map<SchemaVersion, SchemaIndex>();

export function schemaIndex(version: SchemaVersion): SchemaIndex {
  let index = indexes.get(version);
  if (!index) {
    index = new SchemaIndex(schemaFor(version));
    indexes.set(version, index);
  }
  return index;
}

/** The versions other than `version` whose type `typeName` has a child (or attribute) of that name. */
export function versionsWith(typeName: string, name: string, kind: 'element' | 'attribute'): SchemaVersion[] {
  return SCHEMA_VERSIONS.filter((version) => {
    const index = schemaIndex(version);
    return kind === 'element' ? index.childParticle(typeName, name, false) !== undefined : index.attribute(typeName, name) !== undefined;
  });
}
