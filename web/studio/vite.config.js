// The studio's front end: built into dist/, which `lsys studio` serves.
export default {
  base: "/",
  build: { outDir: "dist", emptyOutDir: true, chunkSizeWarningLimit: 1000 },
};
