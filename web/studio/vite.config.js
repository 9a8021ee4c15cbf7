// The studio's front end: built into dist/, which `lsys studio` serves.
// Two pages: the editor (index.html) and the drawing page (drawing.html).
import { fileURLToPath } from "node:url";

const page = (name) => fileURLToPath(new URL(name, import.meta.url));

export default {
  base: "/",
  build: {
    outDir: "dist",
    emptyOutDir: true,
    chunkSizeWarningLimit: 1000,
    rollupOptions: { input: { main: page("index.html"), drawing: page("drawing.html") } },
  },
};
