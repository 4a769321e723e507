import { strict as assert } from 'node:assert';

/**
 * The environment esmini recorded (`esmini --record FILE.dat`): the one place a headless run shows what an
 * EnvironmentAction did, as its CSV log carries entities only. Layout from esmini 3.6.0's
 * EnvironmentSimulator/Modules/ScenarioEngine/SourceFiles/PacketHandler.hpp (DAT format 5.3): a header of
 * uint32 major, minor and payload size, the payload; then packets of uint32 id, uint32 size and data, little-endian.
 */
export interface RecordedEnvironment {
  /** The simulation time of the step it was recorded at. */
  time: number;
  /** Fog visual range (m), 1e10 when no fog is set. */
  visibilityRange: number;
  cloudStateFactor: number;
  /** The sun's intensity, clamped to 0..100000 lx and scaled to 0..1. */
  sunIntensityFactor: number;
  fogVisibilityRangeFactor: number;
  frictionScaleFactor: number;
}

const TIMESTAMP = 5;
const ENVIRONMENT = 29;

export function recordedEnvironments(dat: Buffer): RecordedEnvironment[] {
  assert.equal(dat.readUInt32LE(0), 5, 'an esmini recording of another DAT format than 5.x');
  let offset = 12 + dat.readUInt32LE(8);
  let time = Number.NaN;
  const environments: RecordedEnvironment[] = [];
  while (offset + 8 <= dat.length) {
    const id = dat.readUInt32LE(offset);
    const size = dat.readUInt32LE(offset + 4);
    const data = offset + 8;
    if (id === TIMESTAMP) time = dat.readDoubleLE(data);
    if (id === ENVIRONMENT) {
      assert.equal(size, 40, `an environment packet of ${size} bytes, not 5 doubles`);
      const [visibilityRange, cloudStateFactor, sunIntensityFactor, fogVisibilityRangeFactor, frictionScaleFactor] = [0, 1, 2, 3, 4].map(
        (index) => dat.readDoubleLE(data + 8 * index),
      );
      environments.push({ time, visibilityRange, cloudStateFactor, sunIntensityFactor, fogVisibilityRangeFactor, frictionScaleFactor });
    }
    offset = data + size;
  }
  assert.equal(offset, dat.length, 'the recording ends inside a packet');
  return environments;
}
