import * as assert from 'node:assert/strict';
import { insideFolders, isInsideFolder } from '../../common/src/paths';

describe('insideFolders: one answer for the editor (watchers) and the language server (outputs, watchers)', () => {
  it('holds a folder itself and what lies under it, with or without a trailing separator', () => {
    assert.equal(isInsideFolder('/ws', '/ws'), true);
    assert.equal(isInsideFolder('/ws/a/b.xosc', '/ws'), true);
    assert.equal(isInsideFolder('/ws/a', '/ws/'), true);
    assert.equal(isInsideFolder('/ws/', '/ws'), true);
  });

  it('does not hold a sibling that shares a prefix, the parent, or another tree', () => {
    assert.equal(isInsideFolder('/ws2/a.xosc', '/ws'), false);
    assert.equal(isInsideFolder('/', '/ws'), false);
    assert.equal(isInsideFolder('/other/ws/a', '/ws'), false);
  });

  it('holds a child whose name merely starts with two dots', () => {
    assert.equal(isInsideFolder('/ws/..roads', '/ws'), true);
    assert.equal(isInsideFolder('/ws/../roads', '/ws'), false);
  });

  it('compares Windows paths as Windows does, whatever the platform: the editor writes c:, Node C:', () => {
    assert.equal(isInsideFolder('C:\\Scenarios\\roads', 'c:\\scenarios'), true);
    assert.equal(isInsideFolder('D:\\scenarios\\roads', 'c:\\scenarios'), false);
    assert.equal(isInsideFolder('\\\\server\\share\\roads', '\\\\server\\share'), true);
  });

  it('answers for a list of folders, and no for none', () => {
    assert.equal(insideFolders('/b/x', ['/a', '/b']), true);
    assert.equal(insideFolders('/c/x', ['/a', '/b']), false);
    assert.equal(insideFolders('/a', []), false);
  });
});
