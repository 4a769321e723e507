/** The ZIP reader lives in common/ so that the extension reads packages as the core does. */
export * from '../../../common/src/zip';
