import * as assert from 'node:assert/strict';
import JSZip from 'jszip';
import { childRef, diskRef, displayRef, FileSystemHost, ScenarioStore, SourceRef } from '../../server/src/core/sources';
import { splitDiskPath } from '../../server/src/core/paths';
import { filePathOf, fileUri, packageUriPath, refToUri, untitledRef, UriResolver } from '../../server/src/uris';
import { scenario } from '../support/fixtures';

/** An in-memory disk: files by path; a folder is any path some file lies below. */
function memoryHost(files: Record<string, Uint8Array | string>, separator: '/' | '\\'): FileSystemHost & { asked: string[] } {
  const asked: string[] = [];
  const bytes = (value: Uint8Array | string) => (typeof value === 'string' ? new TextEncoder().encode(value) : value);
  return {
    asked,
    async readFile(filePath) {
      asked.push(filePath);
      const value = files[filePath];
      return value === undefined ? undefined : bytes(value);
    },
    async kind(filePath) {
      asked.push(filePath);
      if (files[filePath] !== undefined) return 'file';
      return Object.keys(files).some((name) => name.startsWith(filePath + separator)) ? 'directory' : undefined;
    },
  };
}

/** `outer.mosc` holding `inner.mosc` (with `main.xosc` and `lib/x.xosc`) and its own `main.xosc`. */
async function nestedPackage(): Promise<Uint8Array> {
  const inner = new JSZip();
  inner.file('main.xosc', scenario(''));
  inner.file('lib/x.xosc', scenario(''));
  const outer = new JSZip();
  outer.file('main.xosc', scenario(''));
  outer.file('inner.mosc', await inner.generateAsync({ type: 'uint8array' }));
  return outer.generateAsync({ type: 'uint8array' });
}

const posixOnly = process.platform === 'win32' ? it.skip : it;

describe('server: file and package URIs on Windows and POSIX paths', () => {
  it('reads Windows file URIs as VS Code spells them into drive-letter paths, and writes them back the same', () => {
    for (const uri of ['file:///c%3A/scenarios/a.mosc', 'file:///C:/scenarios/a.mosc', 'file:///c:/scenarios/a.mosc']) {
      assert.equal(filePathOf(uri), 'C:\\scenarios\\a.mosc', uri);
    }
    assert.equal(refToUri(diskRef('C:\\scenarios\\a.mosc')), 'file:///c%3A/scenarios/a.mosc');
    assert.equal(refToUri(diskRef('C:/scenarios/a.mosc')), 'file:///c%3A/scenarios/a.mosc', 'forward slashes in a Windows path');
    assert.equal(diskRef('C:/scenarios/sub/../a.mosc').disk, 'C:\\scenarios\\a.mosc');
    const spaced = 'C:\\my scenarios\\a#1.xosc';
    assert.equal(refToUri(diskRef(spaced)), 'file:///c%3A/my%20scenarios/a%231.xosc');
    assert.equal(filePathOf(refToUri(diskRef(spaced))), spaced);
  });

  it('reads UNC shares as file URIs with a host, and back', () => {
    assert.equal(filePathOf('file://server/share/scenarios/a.mosc'), '\\\\server\\share\\scenarios\\a.mosc');
    assert.equal(refToUri(diskRef('\\\\server\\share\\scenarios\\a.mosc')), 'file://server/share/scenarios/a.mosc');
  });

  posixOnly('keeps POSIX paths as they are: percent-encoding round-trips, a backslash is an ordinary character', () => {
    const paths = ['/home/user/my scenarios/a#1.xosc', '/srv/odd\\name.xosc', '/tmp/ü.mosc'];
    for (const diskPath of paths) {
      const uri = refToUri(diskRef(diskPath));
      assert.equal(uri, fileUri(diskPath).toString());
      assert.equal(filePathOf(uri), diskPath, uri);
    }
    assert.equal(refToUri(diskRef('/home/user/my scenarios/a#1.xosc')), 'file:///home/user/my%20scenarios/a%231.xosc');
    assert.equal(filePathOf('file:///srv/odd%5Cname.xosc'), '/srv/odd\\name.xosc');
    assert.equal(filePathOf('untitled:Untitled-1'), undefined);
    assert.equal(filePathOf('relative/out.xosc'), undefined, 'a plain path is not read as a URI');
  });

  it('writes mosc: URIs of nested packages with drive letters, and reads them back as one path', () => {
    const ref = childRef(childRef(diskRef('C:\\scenarios\\outer.mosc'), 'inner.mosc'), 'lib/x.xosc');
    const uri = refToUri(ref);
    assert.equal(uri, 'mosc:/c%3A/scenarios/outer.mosc/inner.mosc/lib/x.xosc');
    assert.equal(packageUriPath(uri), 'C:\\scenarios\\outer.mosc\\inner.mosc\\lib\\x.xosc');
    assert.equal(packageUriPath('mosc:///C:/scenarios/outer.mosc/main.xosc?x#y'), 'C:\\scenarios\\outer.mosc\\main.xosc');
    assert.equal(refToUri(childRef(diskRef('\\\\server\\share\\p.mosc'), 'main.xosc')), 'mosc://server/share/p.mosc/main.xosc');
    assert.equal(packageUriPath('mosc://server/share/p.mosc/main.xosc'), '\\\\server\\share\\p.mosc\\main.xosc');
    assert.equal(packageUriPath('file:///c%3A/a.mosc'), undefined);
  });

  posixOnly('writes and reads mosc: URIs of POSIX packages in every authority form', () => {
    const ref = childRef(childRef(diskRef('/abs/my pkg.mosc'), 'inner.mosc'), 'main.xosc');
    assert.equal(refToUri(ref), 'mosc:/abs/my%20pkg.mosc/inner.mosc/main.xosc');
    for (const uri of [
      'mosc:/abs/my%20pkg.mosc/inner.mosc/main.xosc',
      'mosc:///abs/my%20pkg.mosc/inner.mosc/main.xosc',
      'MOSC:/abs/x/../my%20pkg.mosc/inner.mosc/main.xosc',
    ]) {
      assert.equal(packageUriPath(uri), '/abs/my pkg.mosc/inner.mosc/main.xosc', uri);
    }
  });

  it('splits disk paths by their own rules: Windows on both separators, POSIX on / only', () => {
    assert.deepEqual(splitDiskPath('C:\\scenarios/pkg.mosc\\main.xosc'), { root: 'C:\\', names: ['scenarios', 'pkg.mosc', 'main.xosc'] });
    assert.deepEqual(splitDiskPath('\\\\server\\share\\a.mosc'), { root: '\\\\server\\share\\', names: ['a.mosc'] });
    if (process.platform !== 'win32') assert.deepEqual(splitDiskPath('/a\\b/c.mosc'), { root: '/', names: ['a\\b', 'c.mosc'] });
  });

  it('finds the package file and the nested packages of a mosc: URI with a drive letter, backslashes included', async () => {
    const host = memoryHost({ 'C:\\scenarios\\outer.mosc': await nestedPackage() }, '\\');
    const store = new ScenarioStore({ host, scenarioPath: [] });
    const resolver = new UriResolver(() => store);
    const expected: SourceRef = { disk: 'C:\\scenarios\\outer.mosc', entries: ['inner.mosc', 'lib/x.xosc'] };
    const uri = 'mosc:/c%3A/scenarios/outer.mosc/inner.mosc/lib/x.xosc';
    assert.deepEqual(await resolver.toRef(uri), expected);
    assert.deepEqual(await store.refFromPackagePath('C:\\scenarios\\outer.mosc\\inner.mosc\\lib\\x.xosc'), expected);
    assert.deepEqual(await store.refFromPackagePath('C:/scenarios/outer.mosc/inner.mosc\\main.xosc'), {
      disk: 'C:\\scenarios\\outer.mosc',
      entries: ['inner.mosc', 'main.xosc'],
    });
    assert.deepEqual(await store.refFromPackagePath('C:\\scenarios\\outer.mosc\\main.xosc'), {
      disk: 'C:\\scenarios\\outer.mosc',
      entries: ['main.xosc'],
    });
    assert.equal(refToUri(expected), uri, 'the reference writes the URI it was read from');
    assert.equal(await store.refFromPackagePath('D:\\scenarios\\outer.mosc\\main.xosc'), undefined);
    assert.ok(
      host.asked.every((asked) => !asked.includes('/')),
      `the disk is asked in Windows form only: ${host.asked.join(', ')}`,
    );
  });

  posixOnly('finds the package file and the nested packages of a POSIX mosc: URI', async () => {
    const store = new ScenarioStore({ host: memoryHost({ '/abs/outer.mosc': await nestedPackage() }, '/'), scenarioPath: [] });
    const resolver = new UriResolver(() => store);
    const uri = 'mosc:/abs/outer.mosc/inner.mosc/lib/x.xosc';
    const ref = await resolver.toRef(uri);
    assert.deepEqual(ref, { disk: '/abs/outer.mosc', entries: ['inner.mosc', 'lib/x.xosc'] });
    assert.equal(refToUri(ref as SourceRef), uri);
  });

  it('resolves names from a Windows scenario in its folder, its package and its parent folders', async () => {
    const host = memoryHost(
      {
        'C:\\work\\project\\pkg\\main.xosc': scenario(''),
        'C:\\work\\project\\pkg\\own.xosc': scenario(''),
        'C:\\work\\project\\up.xosc': scenario(''),
        'C:\\work\\project\\lib\\main.xosc': scenario(''),
        'C:\\work\\project\\outer.mosc': await nestedPackage(),
        'C:\\work\\above.xosc': scenario(''),
      },
      '\\',
    );
    const store = new ScenarioStore({ host, root: 'C:\\work\\project', scenarioPath: [] });
    const from = diskRef('C:\\work\\project\\pkg\\main.xosc');
    const found = async (name: string, source: SourceRef = from) => {
      const resolution = await store.resolve(name, source);
      if (resolution.kind === 'scenario') return `${resolution.via}:${displayRef(resolution.ref, 'C:\\work')}`;
      if (resolution.kind === 'package') return `${resolution.via}:${displayRef(resolution.main, 'C:\\work')}`;
      return resolution.kind === 'missing' ? `missing:${resolution.searched.join(',')}` : resolution.kind;
    };
    assert.equal(await found('own.xosc'), 'folder:project\\pkg\\own.xosc');
    assert.equal(await found('up.xosc'), 'parent:project\\up.xosc');
    assert.equal(await found('../lib.mosc'), 'folder:project\\lib\\main.xosc', 'an unpacked package folder');
    assert.equal(
      await found('above.xosc'),
      'missing:C:\\work\\project\\pkg,C:\\work\\project (parent folder)',
      'the search stops at the root',
    );
    const inner = childRef(childRef(diskRef('C:\\work\\project\\outer.mosc'), 'inner.mosc'), 'main.xosc');
    assert.equal(
      await found('lib/x.xosc', inner),
      'package:project\\outer.mosc/inner.mosc/lib/x.xosc',
      'entries inside packages stay POSIX',
    );
    assert.equal(await found('../outer.mosc'), 'folder:project\\outer.mosc/main.xosc');
  });

  it('shows Windows references relative to a Windows base, entries after /', () => {
    const ref = childRef(childRef(diskRef('C:\\scenarios\\case\\a.mosc'), 'inner.mosc'), 'main.xosc');
    assert.equal(displayRef(ref, 'C:\\scenarios'), 'case\\a.mosc/inner.mosc/main.xosc');
    assert.equal(displayRef(ref, 'c:\\Scenarios'), 'case\\a.mosc/inner.mosc/main.xosc', 'drive and folder names ignore case on Windows');
    assert.equal(displayRef(ref, 'D:\\scenarios'), 'C:\\scenarios\\case\\a.mosc/inner.mosc/main.xosc');
    assert.equal(displayRef(ref, '/home/user'), 'C:\\scenarios\\case\\a.mosc/inner.mosc/main.xosc', 'a POSIX base never contains a drive');
    if (process.platform !== 'win32') assert.equal(displayRef(childRef(diskRef('/w/s/a.mosc'), 'main.xosc'), '/w'), 's/a.mosc/main.xosc');
  });

  it('places untitled documents in a Windows folder by its own rules', () => {
    assert.equal(untitledRef('untitled:Untitled-1', 'C:\\work')?.disk, 'C:\\work\\.untitled-Untitled-1.xosc');
  });
});
