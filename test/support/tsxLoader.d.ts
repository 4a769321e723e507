/** tsx's loader entry, what `node --import=tsx` loads, ships no types: importing it registers the loader and exports nothing. */
declare module 'tsx' {}
