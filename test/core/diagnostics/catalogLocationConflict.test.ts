import * as assert from 'node:assert/strict';
import {
  CATALOG_LOCATION_CONFLICT,
  catalogLocationConflictKey,
  catalogLocationConflictWording,
} from '../../../server/src/core/diagnostics/catalogLocationConflict';

describe('diagnostics: catalog-location-conflict', () => {
  it("says which directory the imported group needs and which the output keeps, keyed by the catalog's kind", () => {
    assert.deepEqual(catalogLocationConflictWording('VehicleCatalog', '/lib/vehicles', 'catalogs'), {
      severity: 'warning',
      code: 'catalog-location-conflict',
      message:
        "an imported group needs the VehicleCatalog directory /lib/vehicles, but this file's VehicleCatalog is catalogs; OpenSCENARIO allows one directory per catalog kind, so the output keeps this one",
      hint: 'put the catalogs the imported group uses into catalogs, or point VehicleCatalog at /lib/vehicles',
      data: { key: 'location:VehicleCatalog' },
    });
    assert.equal(catalogLocationConflictKey('VehicleCatalog'), 'location:VehicleCatalog');
  });

  it('checks the data a client sends back', () => {
    assert.equal(CATALOG_LOCATION_CONFLICT.isData!({ key: 'location:VehicleCatalog' }), true);
    assert.equal(CATALOG_LOCATION_CONFLICT.isData!({ key: 3 }), false);
    assert.equal(CATALOG_LOCATION_CONFLICT.isData!(undefined), false);
  });
});
