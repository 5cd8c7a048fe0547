// Validates a .glb with the Khronos glTF-Validator and prints its report's counts as one line:
// errors=N warnings=N infos=N. Exits 1 if there is an error, 2 if the file cannot be read.
import { readFile } from 'node:fs/promises';
import validator from 'gltf-validator';

const path = process.argv[2];
let bytes;
try {
  bytes = new Uint8Array(await readFile(path));
} catch (e) {
  console.error(`cannot read ${path}: ${e.message}`);
  process.exit(2);
}
const report = await validator.validateBytes(bytes, { maxIssues: 20 });
const { numErrors, numWarnings, numInfos } = report.issues;
console.log(`errors=${numErrors} warnings=${numWarnings} infos=${numInfos}`);
for (const message of report.issues.messages) console.log(`${message.severity} ${message.code} ${message.pointer ?? ''}: ${message.message}`);
process.exit(numErrors > 0 ? 1 : 0);
