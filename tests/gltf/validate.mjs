// Runs the Khronos glTF validator on each file named on the command line.
// Prints one line per file with its error and warning counts (and the errors themselves),
// and exits non-zero when any file has an error or cannot be read.
//
//   node tests/gltf/validate.mjs out/a.gltf out/b.glb

import { readFile } from "node:fs/promises";
import path from "node:path";
import validator from "gltf-validator";

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error("usage: node tests/gltf/validate.mjs FILE.gltf|FILE.glb ...");
  process.exit(2);
}

let failed = 0;
for (const file of files) {
  try {
    const bytes = new Uint8Array(await readFile(file));
    const dir = path.dirname(file);
    const report = await validator.validateBytes(bytes, {
      uri: path.basename(file),
      // External buffers (.bin) sit beside the .gltf; URIs are percent-encoded.
      externalResourceFunction: (uri) =>
        readFile(path.join(dir, decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
    });
    const { numErrors, numWarnings, numInfos, numHints, messages } = report.issues;
    console.log(
      `${file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos, ${numHints} hints`,
    );
    for (const m of messages) {
      // Severity 0 is an error, 1 a warning; infos and hints are left out.
      if (m.severity <= 1) {
        const kind = m.severity === 0 ? "error" : "warning";
        console.log(`  ${kind} ${m.code} at ${m.pointer ?? "(root)"}: ${m.message}`);
      }
    }
    if (numErrors > 0) failed += 1;
  } catch (e) {
    console.log(`${file}: could not validate: ${e?.message ?? e}`);
    failed += 1;
  }
}
process.exit(failed > 0 ? 1 : 0);
