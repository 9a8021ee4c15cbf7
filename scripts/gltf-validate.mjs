#!/usr/bin/env node
// Validates .gltf/.glb files with the Khronos glTF-Validator (npm package
// `gltf-validator`). Input: file paths as arguments; output: one line per
// file, `path: N errors, M warnings`, followed by each error (and warning)
// message; exit status 1 if any file has errors or cannot be read, 2 on
// usage errors or when the validator package cannot be found.
//
// The package is looked up in `$GLTF_VALIDATOR_DIR/node_modules` first (a
// directory made with `npm install --prefix DIR gltf-validator`, so the
// repository needs no package.json), then by normal Node resolution.

import { readFile } from "node:fs/promises";
import { createRequire } from "node:module";
import path from "node:path";
import process from "node:process";

function loadValidator() {
  const bases = [];
  if (process.env.GLTF_VALIDATOR_DIR) {
    // createRequire resolves relative to a file; any name inside the
    // directory works, it need not exist.
    bases.push(path.join(path.resolve(process.env.GLTF_VALIDATOR_DIR), "noop.js"));
  }
  bases.push(import.meta.url);
  for (const base of bases) {
    try {
      return createRequire(base)("gltf-validator");
    } catch (e) {
      if (e.code !== "MODULE_NOT_FOUND") throw e;
    }
  }
  return null;
}

const SEVERITY = ["error", "warning", "info", "hint"];

async function validate(validator, file) {
  const bytes = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0, // report everything
    // Our files are self-contained; any external reference is a bug.
    externalResourceFunction: (uri) =>
      Promise.reject(new Error(`external resource not allowed: ${uri}`)),
  });
  const { numErrors, numWarnings, messages } = report.issues;
  console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings`);
  for (const m of messages) {
    if (m.severity <= 1) {
      const where = m.pointer ? ` at ${m.pointer}` : "";
      console.log(`  ${SEVERITY[m.severity]} ${m.code}${where}: ${m.message}`);
    }
  }
  return numErrors;
}

async function main() {
  const files = process.argv.slice(2);
  if (files.length === 0) {
    console.error("usage: node scripts/gltf-validate.mjs FILE.glb|FILE.gltf ...");
    return 2;
  }
  const validator = loadValidator();
  if (!validator) {
    console.error(
      "gltf-validator not found: npm install --prefix target/npm gltf-validator " +
        "and set GLTF_VALIDATOR_DIR=target/npm",
    );
    return 2;
  }
  let failed = false;
  for (const file of files) {
    try {
      if ((await validate(validator, file)) > 0) failed = true;
    } catch (e) {
      // validateBytes rejects when the input is neither glTF nor GLB.
      console.log(`${file}: cannot validate: ${e}`);
      failed = true;
    }
  }
  return failed ? 1 : 0;
}

process.exitCode = await main();
