// Validates .glb files with the Khronos glTF validator (npm package gltf-validator) and prints
// its report's counts; exits 1 if any file has an error, 77 (a skip for CTest) if the
// validator is not installed (scripts/setup installs it into .node/).
// Usage: node validate.mjs VALIDATOR_DIR FILE.glb...
import { createRequire } from 'node:module';
import { readFileSync } from 'node:fs';
import path from 'node:path';

const [validatorDir, ...files] = process.argv.slice(2);
let validator;
try {
  validator = createRequire(path.join(path.resolve(validatorDir), 'package.json'))('gltf-validator');
} catch (e) {
  console.log(`gltf-validator is not installed in ${validatorDir} (run scripts/setup): skipped`);
  process.exit(77);
}
let failed = false;
for (const file of files) {
  const report = await validator.validateBytes(new Uint8Array(readFileSync(file)), {
    maxIssues: 50,
  });
  const issues = report.issues;
  console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ` +
              `${issues.numInfos} infos, ${issues.numHints} hints`);
  for (const message of issues.messages) {
    console.log(`  [${['error', 'warning', 'info', 'hint'][message.severity]}] ${message.code} ` +
                `${message.pointer ?? ''}: ${message.message}`);
  }
  if (issues.numErrors > 0) failed = true;
}
process.exit(failed ? 1 : 0);
